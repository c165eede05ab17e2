import pytest
from olive_sim.module_node import read_namespace


def test_no_override_keeps_the_default():
    assert read_namespace('pan', ['servo_sim', '--ros-args', '-r', '__ns:=/x']) == 'pan'


def test_the_last_override_wins_and_parameter_files_count_for_all_nodes(tmp_path):
    params = tmp_path / 'params.yaml'
    params.write_text('/**:\n  ros__parameters:\n    namespace: tilt\n    kp: 2.0\n')
    args = ['servo_sim', '--ros-args', '-p', 'namespace:=pan', '--params-file', str(params)]
    assert read_namespace('x', args) == 'tilt'
    assert read_namespace('x', [*args, '--param', 'namespace:=wrist']) == 'wrist'


def test_arguments_outside_ros_args_are_not_parameters():
    assert read_namespace('pan', ['servo_sim', '-p', 'namespace:=tilt']) == 'pan'


@pytest.mark.parametrize(('args', 'message'), [
    (['--ros-args', '-p', 'namespace:=5'], 'parameter namespace must be a string, got 5'),
    (['--ros-args', '-p', 'namespace:=1pan'], "namespace '1pan' is not valid"),
    (['--ros-args', '--params-file', '/nonexistent.yaml'], "cannot read parameter file '/nonexistent.yaml'"),
])
def test_bad_overrides_are_value_errors(args, message):
    with pytest.raises(ValueError, match=message):
        read_namespace('pan', ['servo_sim', *args])
