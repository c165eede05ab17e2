"""`ros2 doctor hello`'s plain parts: options, names, payloads, the table, the emit loop; no ROS graph."""

import argparse
import os
import socket
import threading
import time

import pytest
import ros2cli.command
from ros2doctor.command.doctor import DoctorCommand
from ros2doctor.verb import hello
from ros2doctor.verb.hello import HelloMulticastUDPReceiver, HelloVerb, SummaryTable


def hello_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog='ros2 doctor hello')
    HelloVerb().add_arguments(parser, 'ros2 doctor hello')
    return parser


def test_defaults_are_upstreams():
    args = hello_parser().parse_args([])
    assert (args.topic, args.emit_period, args.print_period, args.ttl, args.once) == \
        ('/canyouhearme', 0.1, 1.0, None, False)
    assert hello_parser().parse_args(['-t']).topic == '/canyouhearme'  # a bare -t keeps the default
    short = hello_parser().parse_args(['-t', '/x', '-ep', '0.5', '-pp', '2', '--ttl', '3', '-1'])
    assert (short.topic, short.emit_period, short.print_period, short.ttl, short.once) == \
        ('/x', 0.5, 2.0, 3, True)


@pytest.mark.parametrize(('argv', 'error'), [
    (['-ep', '0'], 'argument -ep/--emit-period: value must be a positive float'),
    (['-pp=-1'], 'argument -pp/--print-period: value must be a positive float'),
    (['-ep', 'nan'], 'argument -ep/--emit-period: value must be a positive float'),
    (['--ttl', 'x'], 'argument --ttl: value must be a positive int'),
    (['--ttl', '256'], 'argument --ttl: value must be at most 255'),
])
def test_bad_values_are_a_usage_error(argv, error, capsys):
    with pytest.raises(SystemExit) as exit_:
        hello_parser().parse_args(argv)
    assert exit_.value.code == 2
    assert capsys.readouterr().err.splitlines()[-1] == f'ros2 doctor hello: error: {error}'


def doctor_args(monkeypatch, *argv):
    monkeypatch.setattr(ros2cli.command, 'ARGV', ['doctor', *argv])
    parser = argparse.ArgumentParser(prog='ros2 doctor')
    DoctorCommand().add_arguments(parser, 'ros2 doctor')
    return parser.parse_args(list(argv))


def test_doctor_takes_the_hello_verb_and_keeps_its_own_options(monkeypatch):
    verb = doctor_args(monkeypatch, 'hello', '-ep', '0.5')
    assert isinstance(verb._verb, HelloVerb)
    assert (verb.emit_period, verb.exclude_packages) == (0.5, False)
    own = doctor_args(monkeypatch, '-ep', '-rf', '-iw')
    assert not hasattr(own, '_verb')
    assert (own.exclude_packages, own.report_failed, own.include_warnings) == (True, True, True)


def test_node_name_has_the_hostname_as_a_node_name_can_hold_it():
    assert hello.node_name_prefix('lab-pc.example.org', 42) == 'ros2doctor_lab_pc_example_org_42'
    assert hello.NODE_NAME_PREFIX.endswith(f'_{os.getpid()}')


def test_only_other_hosts_hellos_count():
    assert hello.hello_payload('lab-pc') == "hello, it's me lab-pc"
    assert hello.remote_sender("hello, it's me other-pc", 'lab-pc') == 'other-pc'
    assert hello.remote_sender("hello, it's me lab-pc", 'lab-pc') is None
    assert hello.remote_sender('   ', 'lab-pc') is None  # nothing to tell who sent it


def filled_table() -> SummaryTable:
    table = SummaryTable()
    for _ in range(3):
        table.increment_pub()
        table.increment_send()
        table.increment_sub('other-pc')
    table.increment_sub('a-host-with-a-long-name')
    table.increment_receive('other-pc')
    return table


def test_table_layout_is_upstreams():
    text = filled_table().format_summary('/canyouhearme', 1.0)
    assert text.splitlines() == [
        'MULTIMACHINE COMMUNICATION SUMMARY',
        'Topic: /canyouhearme, Published Msg Count: 3',
        'Subscribed from:',
        '                Hostname             Msg Count /1.0s',
        '                other-pc             3         ',
        '                a-host-with-a-long-name 1         ',
        'Multicast Group/Port: 225.0.0.1/49150, Sent Msg Count: 3',
        'Received from:',
        '                Hostname             Msg Count /1.0s',
        '                other-pc             1         ',
        '-' * 60,
    ]


def test_reset_starts_the_next_period_from_zero(capsys):
    table = filled_table()
    table.reset()
    table.format_print_summary('/t', 2.5)
    assert capsys.readouterr().out.splitlines()[1:5] == [
        'Topic: /t, Published Msg Count: 0', 'Subscribed from:',
        '                Hostname             Msg Count /2.5s',
        'Multicast Group/Port: 225.0.0.1/49150, Sent Msg Count: 0']


class Publisher:
    def __init__(self, table: SummaryTable) -> None:
        self.table = table

    def publish(self) -> None:
        self.table.increment_pub()


class RefusingSender:
    def send(self) -> None:
        raise OSError(101, 'Network is unreachable')

    def shutdown(self) -> None:
        pass


class Clock:
    """Stands in for the time module: the loop's time passes only as the executor spins."""

    def __init__(self) -> None:
        self.now = 0.0

    def monotonic(self) -> float:
        return self.now


class Executor:
    def __init__(self, clock: Clock, stop_at: float | None = None) -> None:
        self.clock = clock
        self.stop_at = stop_at
        self.spun = 0.0

    def spin_once(self, timeout_sec: float) -> None:
        self.clock.now += timeout_sec
        self.spun += timeout_sec
        if self.stop_at is not None and self.clock.now >= self.stop_at:
            raise KeyboardInterrupt  # as Ctrl-C does


def test_once_emits_one_period_and_a_refused_send_is_one_line(capsys, monkeypatch):
    monkeypatch.setattr(hello, 'time', clock := Clock())
    monkeypatch.setattr(hello, '_multicast_off_said', threading.Event())
    table = SummaryTable()
    executor = Executor(clock)
    args = argparse.Namespace(topic='/t', emit_period=0.25, print_period=1.0, once=True)
    hello._emit_until_done(executor, Publisher(table), RefusingSender(), table, args)
    assert executor.spun == 0.25  # the subscription is served for one emit period
    out, err = capsys.readouterr()
    assert out.count('MULTIMACHINE COMMUNICATION SUMMARY') == 1
    assert 'Topic: /t, Published Msg Count: 1' in out
    assert 'Sent Msg Count: 0' in out
    assert err == ('ros2 doctor hello: UDP multicast on 225.0.0.1/49150 does not work here '
                   '(cannot send: [Errno 101] Network is unreachable); the ROS topic part goes on\n')
    hello.say_multicast_off('receive', OSError('again'))
    assert capsys.readouterr().err == ''  # said once per run


def test_tables_are_printed_each_print_period_with_fresh_counts(capsys, monkeypatch):
    monkeypatch.setattr(hello, 'time', clock := Clock())
    table = SummaryTable()
    args = argparse.Namespace(topic='/t', emit_period=0.25, print_period=1.0, once=False)
    with pytest.raises(KeyboardInterrupt):
        hello._emit_until_done(Executor(clock, stop_at=4.0), Publisher(table), None, table, args)
    tables = capsys.readouterr().out.split('MULTIMACHINE COMMUNICATION SUMMARY\n')[1:]
    # Printed once more than a period has passed (at 1.25 s, 2.5 s, 3.75 s), each with that period's count.
    assert [text.splitlines()[0] for text in tables] == ['Topic: /t, Published Msg Count: 5'] * 3


def test_receiver_counts_other_hosts_until_shut_down():
    table = SummaryTable()
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        probe.bind(('127.0.0.1', 0))
        port = probe.getsockname()[1]
    try:
        receiver = HelloMulticastUDPReceiver(table, port=port)
    except OSError as error:
        pytest.skip(f'no multicast-capable interface here: {error}')
    receiving = threading.Thread(target=receiver.recv)
    receiving.start()
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as sender:
        # Ours and a datagram that is no text first: once other-pc's is counted, they have been skipped.
        ours = f"hello, it's me {socket.gethostname()}".encode()
        for payload in (b'\xff', ours, b"hello, it's me other-pc"):
            sender.sendto(payload, ('127.0.0.1', port))
    deadline = time.monotonic() + 5
    while 'other-pc  ' not in table.format_summary('/t', 1.0) and time.monotonic() < deadline:
        time.sleep(0.01)
    receiver.shutdown()
    receiving.join(timeout=2)
    assert not receiving.is_alive()
    received = table.format_summary('/t', 1.0).split('Received from:\n')[1].splitlines()
    assert received[1:-1] == ['                other-pc             1         ']
