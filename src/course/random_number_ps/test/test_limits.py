import random

from random_number_ps.limits import check_limits
from random_number_ps.turtle_random_velocity import random_twist


def test_equal_limits_are_a_range():
    assert check_limits(5, 5) is None


def test_lower_above_upper_is_refused_with_both_values():
    reason = check_limits(10, 3)
    assert reason is not None
    assert '10' in reason
    assert '3' in reason


def test_negative_ranges_are_fine():
    assert check_limits(-50, -1) is None


def test_random_twist_stays_inside_the_limits():
    rng = random.Random(7)
    for _ in range(1000):
        twist = random_twist(rng, 1.5, 0.5)
        assert 0.0 <= twist.linear.x <= 1.5
        assert -0.5 <= twist.angular.z <= 0.5
        assert twist.linear.y == twist.linear.z == twist.angular.x == twist.angular.y == 0.0
