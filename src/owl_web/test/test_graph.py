"""Node Graph's model and layout, from plain graph data."""

from rqt_web.graph_model import BOX_HEIGHT, build_model, layout

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


def test_layers_follow_the_data_flow():
    drawn = layout(build_model(COURSE_GRAPH))
    layer = {box['id']: box['layer'] for box in drawn['boxes']}
    assert layer == {'/teleop_turtle': 0, '/turtle1/cmd_vel': 1, '/turtlesim': 2, '/turtle1/pose': 3}
    x = {box['id']: box['x'] for box in drawn['boxes']}
    assert x['/teleop_turtle'] < x['/turtle1/cmd_vel'] < x['/turtlesim'] < x['/turtle1/pose']
    assert drawn['edges'][0] == {'from': '/teleop_turtle', 'to': '/turtle1/cmd_vel'}
    assert all(box['x'] + box['width'] <= drawn['width'] and box['y'] + BOX_HEIGHT <= drawn['height']
               for box in drawn['boxes'])


def test_cycles_are_laid_out_and_boxes_do_not_overlap():
    # talker <-> echo over two topics, plus a node publishing and subscribing the same topic
    graph = {
        '/a': ([('/ping', ['std_msgs/msg/String'])], [('/pong', ['std_msgs/msg/String'])]),
        '/b': ([('/pong', ['std_msgs/msg/String'])], [('/ping', ['std_msgs/msg/String'])]),
        '/loop': ([('/self', ['std_msgs/msg/Int32'])], [('/self', ['std_msgs/msg/Int32'])]),
        '/idle': ([], []),
    }
    drawn = layout(build_model(graph))
    assert {box['id'] for box in drawn['boxes']} == {'/a', '/b', '/loop', '/idle', '/ping', '/pong', '/self'}
    spots = [(box['layer'], box['y']) for box in drawn['boxes']]
    assert len(spots) == len(set(spots))


def test_empty_graph():
    assert layout(build_model({})) == {'nodes': [], 'topics': [], 'edges': [], 'boxes': [],
                                       'width': 0, 'height': 0}
