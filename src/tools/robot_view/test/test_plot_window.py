"""The live plots' decimation, window and pushes, without a node."""

import math

import pytest
from robot_view.plot_window import LATE, OVERLAP, PlotWindow, PushCursor, sample_time


def window(**kwargs):
    return PlotWindow(('goal', 'position', 'effort'), held=('goal',), **kwargs)


def test_samples_are_averaged_per_bucket_and_a_bucket_without_samples_is_none():
    plot = window(bucket=0.02)
    plot.add(1.000, {'position': 1.0, 'effort': 0.5})
    plot.add(1.010, {'position': 2.0})
    plot.add(1.025, {'effort': -0.25})
    assert plot.columns() == {'t': [1.0, 1.02], 'goal': [None, None], 'position': [1.5, None],
                              'effort': [0.5, -0.25]}


def test_a_goal_is_held_from_its_bucket_on_as_a_step():
    plot = window(bucket=0.02)
    plot.add(0.0, {'position': 0.0})
    plot.add(0.05, {'goal': 1.57})
    for step in range(4, 8):
        plot.add(step * 0.02, {'position': 0.1 * step})
    columns = plot.columns()
    assert columns['t'] == [0.0, 0.04, 0.08, 0.1, 0.12, 0.14]
    assert columns['goal'] == [None, 1.57, 1.57, 1.57, 1.57, 1.57]
    plot.add(0.16, {'goal': 0.0})
    assert plot.columns(since=0.15)['goal'] == [0.0]


def test_100_hz_becomes_50_points_a_second():
    plot = window()  # the default bucket
    for sample in range(1000):  # 10 s at 100 Hz
        plot.add(sample / 100, {'position': math.sin(sample / 100)})
    columns = plot.columns()
    assert len(columns['t']) == 500
    assert columns['position'][250] == pytest.approx(math.sin(5.005), abs=1e-4)


def test_only_the_window_and_the_overlap_are_kept():
    plot = window(bucket=0.1, window=2.0)
    for sample in range(100):  # 10 s
        plot.add(sample * 0.1, {'position': float(sample)})
    times = plot.columns()['t']
    assert times[-1] == pytest.approx(9.9)
    assert times[0] == pytest.approx(9.9 - 2.0 - OVERLAP)


def test_a_late_sample_goes_in_its_own_bucket_and_a_very_late_one_in_the_newest():
    plot = window(bucket=0.02)
    plot.add(1.0, {'position': 1.0})
    plot.add(1.1, {'position': 2.0})
    # handled after a newer message of another topic: in its place, a bucket begun in between
    plot.add(1.04, {'position': 3.0, 'effort': 0.5})
    plot.add(1.0, {'position': 5.0})
    assert plot.columns() == {'t': [1.0, 1.04, 1.1], 'goal': [None] * 3, 'position': [3.0, 3.0, 2.0],
                              'effort': [None, 0.5, None]}
    plot.add(1.1 - LATE - 0.02, {'position': 4.0})  # further behind than a push repeats
    assert plot.columns()['position'] == [3.0, 3.0, 3.0]


def test_a_late_goal_is_held_from_its_own_bucket_up_to_the_next_goal():
    plot = window(bucket=0.02)
    for step in range(10):
        plot.add(step * 0.02, {'position': 0.0})
    plot.add(0.16, {'goal': 2.0})
    plot.add(0.05, {'goal': 1.0})  # sent before the goal of 0.16, handled after it
    assert plot.columns()['goal'] == [None, None, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0, 2.0, 2.0]
    plot.add(0.2, {'position': 0.0})
    assert plot.columns(since=0.2)['goal'] == [2.0]  # a new bucket holds the newest goal
    plot.add(0.19, {'goal': 3.0})  # late, and the newest goal: held on in the buckets to come
    plot.add(0.22, {'position': 0.0})
    assert plot.columns(since=0.15)['goal'] == [2.0, 3.0, 3.0, 3.0]


def test_a_stamp_is_the_sample_time_unless_it_is_from_another_clock():
    now = 1_800_000_000.0
    assert sample_time(None, now) == now
    assert sample_time(int((now - 0.3) * 1e9), now) == pytest.approx(now - 0.3)
    assert sample_time(int((now - 5.0) * 1e9), now) == now  # a module whose clock was never set
    assert sample_time(int((now + 2.0) * 1e9), now) == now  # a clock ahead of this machine's


def test_bad_samples_and_bad_windows_are_refused():
    plot = window()
    with pytest.raises(ValueError, match="unknown series 'speed'"):
        plot.add(0.0, {'speed': 1.0})
    with pytest.raises(ValueError, match='position: nan is not a finite number'):
        plot.add(0.0, {'position': float('nan')})
    assert plot.newest() is None
    with pytest.raises(ValueError, match='held series not among the series: speed'):
        PlotWindow(('goal',), held=('speed',))
    with pytest.raises(ValueError, match='need 0 < bucket < window'):
        PlotWindow(('goal',), bucket=0.0)


def test_a_page_gets_the_window_first_then_what_is_new_with_an_overlap():
    plot = window(bucket=0.1, window=2.0)
    cursor = PushCursor()
    assert cursor.batch(plot) is None  # nothing yet
    for sample in range(30):  # 3 s
        plot.add(sample * 0.1, {'position': float(sample)})
    first = cursor.batch(plot)
    assert first['t'][0] == pytest.approx(2.9 - 2.0 - OVERLAP)
    assert first['t'][-1] == pytest.approx(2.9)
    assert cursor.batch(plot) is None  # no new bucket
    plot.add(3.0, {'position': 30.0})
    second = cursor.batch(plot)
    # from OVERLAP before the last batch's newest bucket: a replaced update loses nothing
    assert second['t'] == pytest.approx([2.4, 2.5, 2.6, 2.7, 2.8, 2.9, 3.0])
    assert second['position'][-1] == 30.0


def test_a_batch_made_while_the_last_waits_to_be_sent_begins_where_that_one_began():
    """owl_web replaces a waiting update: however many are replaced, the page's plot has no gap."""
    plot = window(bucket=0.1, window=2.0)
    cursor = PushCursor()
    plot.add(0.0, {'position': 0.0})
    cursor.batch(plot)  # sent
    plot.add(1.0, {'position': 10.0})
    waiting = cursor.batch(plot)
    assert waiting['t'] == [0.0, 1.0]  # from OVERLAP before the sent one's newest bucket (0.0)
    for sample in range(11, 20):  # each batch takes the place of the one before, never sent
        plot.add(sample * 0.1, {'position': float(sample)})
        replacing = cursor.batch(plot, last_sent=False)
        assert replacing['t'][0] == waiting['t'][0]
        assert replacing['t'][-1] == pytest.approx(sample * 0.1)
    plot.add(2.0, {'position': 20.0})
    after_sent = cursor.batch(plot)  # the last one went: back to the overlap
    assert after_sent['t'][0] == pytest.approx(1.9 - OVERLAP)
