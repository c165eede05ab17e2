import itertools
import threading
import time

import pytest
from owl_common.periodic import PeriodicThread, next_call, scheduled_time, wall_time_ns


def test_calls_at_its_rate_until_stopped_then_finishes_on_its_own_thread():
    calls, finished_on = [], []
    periodic = PeriodicThread(100.0, lambda: calls.append(threading.current_thread()), 'test',
                              alive=lambda: True,
                              finish=lambda: finished_on.append(threading.current_thread()))
    time.sleep(0.3)
    periodic.stop()
    count = len(calls)
    time.sleep(0.05)
    assert len(calls) == count  # no call after stop()
    assert count >= 1
    assert set(calls) == set(finished_on)
    assert finished_on[0] is not threading.current_thread()


def test_a_failing_callback_ends_quietly_once_its_context_is_gone(capsys):
    def fail():
        raise RuntimeError('context is not valid')

    finished = threading.Event()
    periodic = PeriodicThread(100.0, fail, 'test', alive=lambda: False, finish=finished.set)
    assert finished.wait(2.0)
    periodic.stop()
    assert 'Traceback' not in capsys.readouterr().err


@pytest.mark.parametrize('rate', [0.1, 50.0])
def test_stop_does_not_wait_for_the_next_call(rate):
    periodic = PeriodicThread(rate, lambda: None, 'test', alive=lambda: True)
    time.sleep(0.05)
    started = time.monotonic()
    periodic.stop()
    # stop() gives up waiting after 2 s, so the thread itself must be gone, well before the 0.1 Hz
    # thread's next call (10 s away).
    assert not periodic._thread.is_alive()
    assert time.monotonic() - started < 1.0


def test_the_schedule_does_not_drift_and_waits_for_the_next_call():
    assert next_call(10.0, 10.004, 0.01, 0.0) == pytest.approx((10.01, 0.006))


def test_calls_held_up_are_made_up_back_to_back_within_catch_up():
    # A 100 Hz sensor held up 0.15 s: its missed samples go out at once, one by one.
    assert next_call(10.0, 10.15, 0.01, 0.2) == pytest.approx((10.01, -0.14))
    assert next_call(10.01, 10.15, 0.01, 0.2) == pytest.approx((10.02, -0.13))


def test_further_behind_than_catch_up_or_one_period_the_schedule_restarts():
    assert next_call(10.0, 10.35, 0.01, 0.2) == (10.35, 0.0)
    assert next_call(10.0, 10.025, 0.01, 0.0) == (10.025, 0.0)  # no catch_up: one period late at most
    assert next_call(10.0, 10.019, 0.01, 0.0) == pytest.approx((10.01, -0.009))


def test_a_call_held_up_keeps_its_due_time_and_the_schedule_goes_on():
    due_times = []

    def call():
        due_times.append(scheduled_time())
        if len(due_times) == 2:
            time.sleep(0.05)  # the machine holds the thread up for five periods

    periodic = PeriodicThread(100.0, call, 'test', alive=lambda: True, catch_up=5.0)
    deadline = time.monotonic() + 5.0
    while len(due_times) < 12 and time.monotonic() < deadline:
        time.sleep(0.01)
    periodic.stop()
    gaps = [later - earlier for earlier, later in itertools.pairwise(due_times[:12])]
    assert gaps == pytest.approx([0.01] * 11, abs=1e-9)


def test_a_hold_up_longer_than_catch_up_is_reported_with_the_calls_skipped():
    reports = []

    def call():
        if not reports and scheduled_time() > started + 0.02:
            time.sleep(0.25)  # the machine holds the thread up for 25 periods, beyond catch_up

    started = time.monotonic()
    periodic = PeriodicThread(100.0, call, 'test', alive=lambda: True, catch_up=0.1,
                              skipped=lambda count, jump: reports.append((count, jump)))
    deadline = time.monotonic() + 5.0
    while not reports and time.monotonic() < deadline:
        time.sleep(0.01)
    time.sleep(0.1)
    periodic.stop()
    assert reports, 'no hold-up reported'
    count, jump = reports[0]  # (a busy machine may hold the thread up again later)
    assert count >= 24, reports
    assert jump == pytest.approx((count + 1) * 0.01, abs=0.005), reports


def test_wall_time_at_a_monotonic_instant_is_not_skewed_by_a_hold_up_between_the_clock_readings(monkeypatch):
    # One timeline: the wall clock reads monotonic + 1000 s, each reading takes 100 ns, and the
    # machine holds the thread up 3 ms right after its first reading.
    now = [5_000_000_000]

    def reading(offset):
        value = now[0] + offset
        now[0] += 3_000_000 if now[0] == 5_000_000_000 else 100
        return value

    monkeypatch.setattr(time, 'monotonic_ns', lambda: reading(0))
    monkeypatch.setattr(time, 'time_ns', lambda: reading(1_000_000_000_000))
    assert abs(wall_time_ns(7.5) - 1_007_500_000_000) <= 100


def test_wall_time_follows_the_system_clock():
    assert abs(wall_time_ns(time.monotonic()) - time.time_ns()) < 5_000_000
