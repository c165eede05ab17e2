"""The graph model our pages draw (rqt's Node Graph), from plain graph data."""

import pytest
from owl_web.codec import ApiError
from owl_web.graph import build_model, graph_options

TWIST = ['geometry_msgs/msg/Twist']
POSE = ['turtlesim/msg/Pose']
LOG = ['rcl_interfaces/msg/Log']
EVENTS = ['rcl_interfaces/msg/ParameterEvent']

# The course's figure 2: teleop_turtle drives turtlesim.
COURSE_GRAPH = {
    '/turtlesim': ([('/turtle1/pose', POSE), ('/rosout', LOG), ('/parameter_events', EVENTS)],
                   [('/turtle1/cmd_vel', TWIST), ('/parameter_events', EVENTS)]),
    '/teleop_turtle': ([('/turtle1/cmd_vel', TWIST), ('/rosout', LOG)], []),
    '/_ros2cli_daemon_0': ([('/rosout', LOG)], []),
}


def test_arrows_go_from_publisher_to_topic_to_subscriber():
    model = build_model(COURSE_GRAPH)
    assert model.nodes == ['/teleop_turtle', '/turtlesim']  # hidden nodes are debug nodes
    assert model.topics == {'/turtle1/cmd_vel': TWIST, '/turtle1/pose': POSE}
    assert sorted(model.edges) == [('/teleop_turtle', '/turtle1/cmd_vel'),
                                   ('/turtle1/cmd_vel', '/turtlesim'), ('/turtlesim', '/turtle1/pose')]


def test_debug_nodes_and_topics_show_on_request_and_leaf_topics_hide_on_request():
    shown = build_model(COURSE_GRAPH, hide_debug=False)
    assert {'/rosout', '/parameter_events'} <= set(shown.topics)
    assert ('/parameter_events', '/turtlesim') in shown.edges
    assert ('/_ros2cli_daemon_0', '/rosout') in shown.edges
    leafless = build_model(COURSE_GRAPH, hide_leaf_topics=True)
    assert list(leafless.topics) == ['/turtle1/cmd_vel']  # /turtle1/pose has no subscriber


def test_hidden_topics_are_debug_topics():
    graph = {'/fibonacci_server': ([('/fibonacci/_action/status', ['action_msgs/msg/GoalStatusArray'])], [])}
    assert build_model(graph).topics == {}
    assert list(build_model(graph, hide_debug=False).topics) == ['/fibonacci/_action/status']


def test_cycles_and_lonely_nodes_are_kept():
    # talker <-> echo over two topics, plus a node publishing and subscribing the same topic
    graph = {
        '/a': ([('/ping', ['std_msgs/msg/String'])], [('/pong', ['std_msgs/msg/String'])]),
        '/b': ([('/pong', ['std_msgs/msg/String'])], [('/ping', ['std_msgs/msg/String'])]),
        '/loop': ([('/self', ['std_msgs/msg/Int32'])], [('/self', ['std_msgs/msg/Int32'])]),
        '/idle': ([], []),
    }
    model = build_model(graph)
    assert model.nodes == ['/a', '/b', '/idle', '/loop']
    assert sorted(model.edges) == [('/a', '/ping'), ('/b', '/pong'), ('/loop', '/self'), ('/ping', '/b'),
                                   ('/pong', '/a'), ('/self', '/loop')]


def test_the_pages_own_node_shows_while_it_publishes_or_subscribes_a_shown_topic():
    rqt = '/rqt_gui_py_node_42'
    quiet = {**COURSE_GRAPH, rqt: ([('/rosout', LOG)], [('/parameter_events', EVENTS)])}
    assert rqt not in build_model(quiet, own_node=rqt).nodes  # only debug topics: no box
    assert rqt in build_model(quiet, hide_debug=False, own_node=rqt).nodes
    publishing = {**COURSE_GRAPH, rqt: ([('/turtle1/cmd_vel', TWIST), ('/rosout', LOG)], [])}
    model = build_model(publishing, own_node=rqt)  # rqt's Message Publisher drives the turtle
    assert rqt in model.nodes
    assert (rqt, '/turtle1/cmd_vel') in model.edges
    # another node with nothing shown keeps its box, as rqt_graph draws it
    assert '/idle' in build_model({'/idle': ([], [])}, own_node=rqt).nodes


def test_as_json_is_what_the_page_gets():
    assert build_model({}).as_json() == {'nodes': [], 'topics': [], 'edges': []}
    assert build_model(COURSE_GRAPH).as_json() == {
        'nodes': ['/teleop_turtle', '/turtlesim'],
        'topics': [{'name': '/turtle1/cmd_vel', 'types': TWIST}, {'name': '/turtle1/pose', 'types': POSE}],
        'edges': [{'from': '/teleop_turtle', 'to': '/turtle1/cmd_vel'},
                  {'from': '/turtle1/cmd_vel', 'to': '/turtlesim'},
                  {'from': '/turtlesim', 'to': '/turtle1/pose'}]}


def test_options_of_a_subscription():
    assert graph_options({}) == (True, False)  # rqt_graph's defaults
    assert graph_options({'hide_debug': False, 'hide_leaf_topics': True}) == (False, True)
    with pytest.raises(ApiError, match="unknown key 'hide_leafs' \\(did you mean 'hide_leaf_topics'\\?\\)"):
        graph_options({'hide_leafs': True})
    with pytest.raises(ApiError, match='hide_debug must be true or false, got "no"'):
        graph_options({'hide_debug': 'no'})
