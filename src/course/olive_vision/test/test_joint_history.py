import pytest
from olive_vision.joint_history import KEEP_NS, JointHistory


def history(*samples: tuple[int, float]) -> JointHistory:
    kept = JointHistory()
    for stamp, position in samples:
        kept.add(stamp, position)
    return kept


def test_a_stamp_between_two_joint_states_gets_the_position_between_them():
    kept = history((1_000, 0.0), (2_000, 0.5), (3_000, 1.0))
    assert kept.at(2_500) == pytest.approx(0.75)
    assert kept.at(2_000) == 0.5
    assert kept.at(1_000) == 0.0


def test_a_stamp_outside_the_history_or_none_gets_the_latest_position():
    kept = history((1_000, 0.0), (2_000, 0.5))
    assert kept.at(5_000) == 0.5  # a picture newer than the last joint state
    assert kept.at(0) == 0.5  # unstamped, or another clock
    assert JointHistory().at(1_000) is None
    assert JointHistory().latest() is None


def test_only_the_last_keep_ns_are_kept_and_a_stamp_going_back_starts_anew():
    kept = history((0, 0.0), (KEEP_NS // 2, 0.2), (KEEP_NS + 1, 0.4))
    assert kept.at(KEEP_NS // 4) == 0.4  # the first sample is gone: before the history now
    kept.add(10, 0.9)  # the servo restarted with another clock
    assert kept.at(KEEP_NS // 2) == 0.9
    assert kept.latest() == 0.9
