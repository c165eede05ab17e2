"""The node-free parts of a module's page: process samples, traffic counters, log book, restart handover."""

import json
import time

import pytest
from olive_sim import restart
from olive_sim.module_log import LogBook, RecordingLogger
from olive_sim.process_stats import ProcessSampler, TrafficMeter, process_cpu_seconds, resident_bytes


def test_samples_are_rates_since_the_previous_one():
    traffic = TrafficMeter()
    counter = traffic.counter()
    clock = iter([10.0, 12.0])
    cpu = iter([1.0, 1.5])
    sampler = ProcessSampler(traffic, cpu_seconds=lambda: next(cpu), memory=lambda: 50_000_000,
                             total_memory=1_000_000_000, clock=lambda: next(clock), wall=lambda: 99.0)
    first = sampler.sample()
    assert (first.cpu, first.tx, first.rx) == (0.0, 0, 0)
    counter.sent += 4000
    counter.received += 100
    second = sampler.sample()
    assert second.cpu == pytest.approx(25.0)   # 0.5 s of CPU in 2 s
    assert (second.tx, second.rx) == (2000, 50)
    assert second.memory == pytest.approx(5.0)
    assert second.memory_mb == 50.0
    assert second.time == 99.0


def test_this_process_has_resident_memory():
    assert resident_bytes() > 1_000_000


def test_a_millisecond_of_work_shows_in_the_cpu_time():
    # A module using under 1 % of a core must not chart 0 %: 10 ms clock ticks showed 0 or 10 ms here.
    before = process_cpu_seconds()
    end = time.perf_counter() + 0.001
    while time.perf_counter() < end:
        pass
    assert 0 < process_cpu_seconds() - before < 0.009


class FakeLogger:
    def __init__(self):
        self.lines = []

    def info(self, message, **kwargs):
        self.lines.append(message)
        return not kwargs.get('filtered', False)

    def get_child(self, name):
        return name


def test_the_log_book_keeps_what_the_logger_emitted_and_tells_listeners():
    book = LogBook(kept=3, clock=lambda: 1.0)
    logger = RecordingLogger(FakeLogger(), book)
    heard = []
    assert book.listen(heard.append) == []
    for n in range(4):
        logger.info(f'line {n}')
    logger.info('filtered out', filtered=True)
    assert [line['message'] for line in book.lines()] == ['line 1', 'line 2', 'line 3']
    assert [line['n'] for line in heard] == [1, 2, 3, 4]
    assert logger.get_child('x') == 'x'  # the rest is the rclpy logger's
    book.forget(heard.append)
    logger.info('unheard')
    assert len(heard) == 4


def test_a_handover_is_taken_out_of_the_environment(monkeypatch):
    monkeypatch.setenv(restart.HANDOVER_VARIABLE, json.dumps({'servo': {'position': 0.5}}))
    assert restart.take_handover() == {'servo': {'position': 0.5}}
    assert restart.take_handover() == {}


def test_a_bad_handover_starts_afresh_with_one_line(monkeypatch, capsys):
    monkeypatch.setenv(restart.HANDOVER_VARIABLE, '[1, 2')
    assert restart.take_handover() == {}
    assert capsys.readouterr().err.count('\n') == 1
