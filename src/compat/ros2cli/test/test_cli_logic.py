"""Node-free logic of the verbs: interface definitions, rate statistics, parameter files."""

import pytest
from ros2cli.verb.interface.show import nested_type, render_definition, split_comment
from ros2cli.verb.param.dump import nested_parameters
from ros2cli.verb.param.load import parameters_for_node
from ros2cli.verb.topic.bw import BandwidthStatistics, size_text
from ros2cli.verb.topic.hz import RateStatistics


def test_interface_lines():
    assert split_comment('string a "#x" # note') == ('string a "#x"', '# note')
    assert nested_type('Vector3  linear', 'geometry_msgs') == ('geometry_msgs', 'Vector3')
    assert nested_type('std_msgs/Header header', 'sensor_msgs') == ('std_msgs', 'Header')
    assert nested_type('geometry_msgs/Pose[] poses', 'x') == ('geometry_msgs', 'Pose')
    assert nested_type('string<=5 name', 'x') is None
    assert nested_type('bool FLAG=true', 'x') is None


def test_render_expands_nested_types_with_tabs():
    rendered = render_definition(['# top', 'Vector3 v # why', ''], 'geometry_msgs', 'default')
    assert rendered == ['# top', 'Vector3 v # why', '\tfloat64 x', '\tfloat64 y', '\tfloat64 z', '']
    assert render_definition(['# top', 'Vector3 v # why'], 'geometry_msgs', 'none') == [
        'Vector3 v', '\tfloat64 x', '\tfloat64 y', '\tfloat64 z']


def test_rate_statistics():
    statistics = RateStatistics(window=100)
    reports = []
    for index in range(31):
        statistics.add(index * 0.1)
        if statistics.due(index * 0.1):
            reports.append(statistics.report())
    assert len(reports) == 3
    assert reports[-1].startswith('average rate: 10.000\n\tmin: 0.100s max: 0.100s std dev: 0.00000s '
                                  'window: 30')
    assert not statistics.add(0.0)  # the clock went back: counters reset
    assert not statistics.intervals


def test_bandwidth_statistics():
    statistics = BandwidthStatistics(window=10)
    for index in range(11):
        statistics.add(index * 0.1, 2000)
    assert statistics.report() == ('20.00 KB/s from 10 messages\n\tMessage size mean: 2.00 KB '
                                      'min: 2.00 KB max: 2.00 KB')
    assert size_text(12) == '12 B'
    assert size_text(3_500_000) == '3.50 MB'


def test_parameter_file_shapes(tmp_path):
    import yaml

    def parameter_file(document):
        path = tmp_path / 'parameters.yaml'
        path.write_text(yaml.safe_dump(document))
        return str(path)

    document = {'/**': {'ros__parameters': {'x': 1, 'y': 'w'}},
                '/node': {'ros__parameters': {'y': 'n', 'z': {'k': [1.5, 2.5]}}},
                '/other': {'ros__parameters': {'x': 9}}}
    parameters = {p.name: p for p in parameters_for_node(parameter_file(document), '/node', True)}
    assert sorted(parameters) == ['x', 'y', 'z.k']
    assert parameters['y'].value.string_value == 'n'
    assert list(parameters['z.k'].value.double_array_value) == [1.5, 2.5]
    only_base_name = parameter_file({'node': {'ros__parameters': {'a': True}}})
    assert [p.name for p in parameters_for_node(only_base_name, '/node', False)] == ['a']
    with pytest.raises(RuntimeError, match="nothing for /node \\(did you mean '/nod'\\?\\); it has: /nod"):
        parameters_for_node(parameter_file({'/nod': {'ros__parameters': {}}}), '/node', True)
    with pytest.raises(RuntimeError, match='not a valid ROS parameter file for node /node'):
        parameters_for_node(parameter_file({'/node': {'x': 1}}), '/node', True)
    with pytest.raises(RuntimeError, match='not a ROS parameter file'):
        parameters_for_node(parameter_file([1, 2]), '/node', True)


def test_nested_parameters_for_dump():
    from rcl_interfaces.msg import ParameterValue
    values = [ParameterValue(type=2, integer_value=1), ParameterValue(type=7, integer_array_value=[1, 2])]
    assert nested_parameters(['a.b', 'c'], values) == {'a': {'b': 1}, 'c': [1, 2]}


def test_python_value_gives_what_rclpy_gives_for_every_parameter_type():
    from rcl_interfaces.msg import ParameterValue
    from rclpy.parameter import parameter_value_to_python
    from ros2cli.api.param import python_value

    fields = [{}, {'bool_value': True}, {'integer_value': 5}, {'double_value': 2.5}, {'string_value': 'x'},
              {'byte_array_value': [b'a']}, {'bool_array_value': [True]}, {'integer_array_value': [1, 2]},
              {'double_array_value': [1.5]}, {'string_array_value': ['a']}]
    values = [ParameterValue(type=kind, **held) for kind, held in enumerate(fields)]
    for value in values:
        assert repr(python_value(value)) == repr(parameter_value_to_python(value))
