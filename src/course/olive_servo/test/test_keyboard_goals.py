"""keyboard_servos' pure logic: which arrow moves which servo which way, the speed, the bounds."""

import pytest
from olive_servo.goals import ARROW_KEYS, KIT_BOUNDS, MAX_STEP_TIME, KeyboardGoals, key_directions


def test_each_arrow_moves_one_servo_the_documented_way():
    # REP 103: positive pan turns the head left, positive tilt turns the camera down.
    assert key_directions({'left'}) == {'pan': +1, 'tilt': 0}
    assert key_directions({'right'}) == {'pan': -1, 'tilt': 0}
    assert key_directions({'up'}) == {'pan': 0, 'tilt': -1}
    assert key_directions({'down'}) == {'pan': 0, 'tilt': +1}
    assert set(ARROW_KEYS) == {'left', 'right', 'up', 'down'}


def test_no_key_opposite_keys_and_other_keys_move_nothing():
    assert key_directions(set()) == {'pan': 0, 'tilt': 0}
    assert key_directions({'left', 'right', 'up', 'down'}) == {'pan': 0, 'tilt': 0}
    assert key_directions({'a', 'space'}) == {'pan': 0, 'tilt': 0}


def test_both_servos_move_at_once():
    assert key_directions({'left', 'up'}) == {'pan': +1, 'tilt': -1}


def test_the_goals_start_at_the_centre():
    goals = KeyboardGoals()
    assert goals.advance(set(), 1.0, 0.01, KIT_BOUNDS) == {'pan': 0.0, 'tilt': 0.0}


def test_a_held_key_moves_its_goal_by_speed_times_time():
    goals = KeyboardGoals()
    for _ in range(50):
        now = goals.advance({'left'}, 2.0, 0.01, KIT_BOUNDS)
    assert now['pan'] == pytest.approx(1.0)  # 2 rad/s for 0.5 s
    assert now['tilt'] == 0.0
    for _ in range(10):
        now = goals.advance({'down'}, 0.5, 0.02, KIT_BOUNDS)
    assert now == pytest.approx({'pan': 1.0, 'tilt': 0.1})
    now = goals.advance(set(), 2.0, 0.05, KIT_BOUNDS)
    assert now == pytest.approx({'pan': 1.0, 'tilt': 0.1})  # released: the goals stay


def test_a_stalled_timer_moves_the_goal_by_at_most_one_capped_step():
    goals = KeyboardGoals()
    assert goals.advance({'left'}, 1.0, 3.0, KIT_BOUNDS)['pan'] == pytest.approx(MAX_STEP_TIME)
    assert goals.advance({'left'}, 1.0, -1.0, KIT_BOUNDS)['pan'] == pytest.approx(MAX_STEP_TIME)


@pytest.mark.parametrize(('key', 'servo', 'limit'), [
    ('left', 'pan', KIT_BOUNDS['pan'][1]), ('right', 'pan', KIT_BOUNDS['pan'][0]),
    ('down', 'tilt', KIT_BOUNDS['tilt'][1]), ('up', 'tilt', KIT_BOUNDS['tilt'][0]),
])
def test_a_key_held_past_the_limit_stops_the_goal_at_the_bound(key, servo, limit):
    goals = KeyboardGoals()
    seen = [goals.advance({key}, 6.0, 0.01, KIT_BOUNDS)[servo] for _ in range(500)]
    assert seen[-1] == limit
    low, high = KIT_BOUNDS[servo]
    assert all(low <= value <= high for value in seen)


def test_narrowed_bounds_bring_the_goal_back_even_with_no_key_held():
    goals = KeyboardGoals()
    for _ in range(100):
        goals.advance({'left'}, 1.0, 0.01, KIT_BOUNDS)
    narrow = {'pan': (-0.5, 0.5), 'tilt': KIT_BOUNDS['tilt']}
    assert goals.advance(set(), 1.0, 0.01, narrow)['pan'] == 0.5


def test_bounds_that_exclude_the_centre_start_the_goal_at_the_nearest_bound():
    goals = KeyboardGoals()
    assert goals.advance(set(), 1.0, 0.01, {'pan': (0.2, 1.0), 'tilt': (-1.0, -0.3)}) == {
        'pan': 0.2, 'tilt': -0.3}
