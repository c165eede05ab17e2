"""The page's commands (set_gains, torque, goal, place_ball), checked without a node."""

import math

import pytest
from owl_web.codec import ApiError
from robot_view.controls import (
    appendix_goals,
    ball_request,
    control_limits,
    gains_request,
    goal_request,
    servo_node,
    torque_request,
)


def refused(function, arguments):
    with pytest.raises(ApiError) as error:
        function(arguments)
    assert '\n' not in error.value.message
    return error.value.message


def test_gains_within_servo_sims_ranges():
    assert gains_request({'servo': 'pan', 'kp': 1, 'ki': 0, 'kd': 0.0}) == \
        ('pan', {'kp': 1.0, 'ki': 0.0, 'kd': 0.0})
    assert gains_request({'servo': 'tilt', 'kd': 10}) == ('tilt', {'kd': 10.0})
    assert gains_request({'servo': 'pan', 'ki': 1000}) == ('pan', {'ki': 1000.0})


@pytest.mark.parametrize(('arguments', 'error'), [
    ({'servo': 'pan', 'kp': 100.5}, 'pan kp must be within 0..100, got 100.5'),
    ({'servo': 'pan', 'kp': -1}, 'pan kp must be within 0..100, got -1'),
    ({'servo': 'pan', 'ki': 1001}, 'pan ki must be within 0..1000, got 1001'),
    ({'servo': 'tilt', 'kd': 11}, 'tilt kd must be within 0..10, got 11'),
    ({'servo': 'pan', 'kp': float('inf')}, 'pan kp must be finite, got inf'),
    ({'servo': 'pan', 'kp': float('nan')}, 'pan kp must be finite, got nan'),
    ({'servo': 'pan', 'kp': '5'}, 'pan kp must be a number, got "5"'),
    ({'servo': 'pan', 'kp': None}, 'pan kp must be a number, got null'),
    ({'servo': 'pan', 'kp': True}, 'pan kp must be a number, got true'),
    ({'servo': 'pan'}, 'set_gains needs at least one of kp, ki, kd'),
    ({'kp': 1}, "missing key 'servo'"),
    ({'servo': 'pan', 'Kp': 1}, "unknown key 'Kp'; expected: servo, kp, ki, kd"),
    ({'servo': 'elbow', 'kp': 1}, 'unknown servo "elbow"; known: pan, tilt'),
    ({'servo': 'Pan', 'kp': 1}, 'unknown servo "Pan" (did you mean \'pan\'?); known: pan, tilt'),
    ({'servo': ['pan'], 'kp': 1}, 'unknown servo ["pan"]; known: pan, tilt'),
])
def test_bad_gains_are_refused_in_one_line(arguments, error):
    assert refused(gains_request, arguments).startswith(error)


def test_torque_takes_a_servo_and_true_or_false():
    assert torque_request({'servo': 'tilt', 'enabled': True}) == ('tilt', True)
    assert torque_request({'servo': 'pan', 'enabled': False}) == ('pan', False)
    assert refused(torque_request, {'servo': 'pan', 'enabled': 1}) == '"enabled" must be true or false, got 1'
    assert refused(torque_request, {'servo': 'pan'}) == "missing key 'enabled'"
    assert refused(torque_request, {'servo': 'head', 'enabled': True}).startswith('unknown servo "head"')


def test_goals_within_the_kits_range_of_each_servo():
    assert goal_request({'servo': 'pan', 'position': 1.57}) == ('pan', 1.57)
    assert goal_request({'servo': 'pan', 'position': 0}) == ('pan', 0.0)
    assert goal_request({'servo': 'tilt', 'position': -1.3}) == ('tilt', -1.3)
    assert refused(goal_request, {'servo': 'tilt', 'position': 1.57}) == \
        'the tilt goal must be within -1.3..0.9, got 1.57'
    assert refused(goal_request, {'servo': 'pan', 'position': 3.2}) == \
        'the pan goal must be within -1.5708..1.5708, got 3.2'
    assert refused(goal_request, {'servo': 'pan', 'position': float('-inf')}) == \
        'the pan goal must be finite, got -inf'
    assert refused(goal_request, {'servo': 'pan', 'goal': 1}).startswith("unknown key 'goal'")


def test_the_servos_node_is_the_courses():
    assert servo_node('pan') == '/olive_servo_pan_dcm_srv'


def test_the_pages_goal_buttons_are_the_appendixs_within_each_range():
    assert appendix_goals('pan') == [0.0, 1.57]
    assert appendix_goals('tilt') == [0.0, 0.9]
    limits = control_limits()
    assert limits['gains'] == {'kp': 100.0, 'ki': 1000.0, 'kd': 10.0}
    assert limits['servos']['tilt'] == {
        'range': [-1.3, 0.9], 'goals': [0.0, 0.9], 'goal_topic': '/olive/servo/tilt/goal/position',
        'torque_services': ['/olive/servo/tilt/setTorqueEnable', '/olive/servo/tilt/setTorqueDisable']}


def test_a_ball_place_is_two_finite_numbers_with_the_azimuth_taken_round():
    assert ball_request({'azimuth': 0.3, 'elevation': -0.1}) == pytest.approx((0.3, -0.1))
    assert ball_request({'azimuth': 2 * math.pi + 0.2, 'elevation': 0}) == pytest.approx((0.2, 0.0))
    assert ball_request({'azimuth': 3.5, 'elevation': 0})[0] == pytest.approx(3.5 - 2 * math.pi)
    # The ball's world is the camera's to judge: an elevation of 1.0 goes to it, and it says no.
    assert ball_request({'azimuth': 0, 'elevation': 1.0}) == pytest.approx((0.0, 1.0))


@pytest.mark.parametrize(('arguments', 'error'), [
    ({'azimuth': 0.1}, "missing key 'elevation'"),
    ({'azimuth': 'left', 'elevation': 0}, 'the ball\'s azimuth must be a number, got "left"'),
    ({'azimuth': 0, 'elevation': math.nan}, "the ball's elevation must be finite, got nan"),
    ({'azimuth': True, 'elevation': 0}, "the ball's azimuth must be a number, got true"),
    ({'azimuth': 0, 'elevation': 0, 'speed': 1}, "unknown key 'speed'"),
])
def test_bad_ball_places_are_refused_in_one_line(arguments, error):
    assert refused(ball_request, arguments).startswith(error)
