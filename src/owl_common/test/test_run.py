import signal

import pytest
import rclpy
from owl_common.run import (
    StopRequest,
    init_with_stop_request,
    interrupt_between_callbacks,
    spin_until_stopped,
)
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.signals import SignalHandlerOptions


def test_a_stop_before_the_main_loop_interrupts_what_the_main_thread_is_doing():
    stop = StopRequest()
    with pytest.raises(KeyboardInterrupt):
        stop(signal.SIGINT, None)
    assert stop.requested


def test_a_stop_during_the_main_loop_is_only_recorded_for_it():
    stop = StopRequest()
    stop.polling = True
    stop(signal.SIGTERM, None)
    assert stop.requested


def test_a_stop_while_the_loop_makes_its_executor_is_raised_by_the_loop_not_inside_the_executor(monkeypatch):
    handlers = {signum: signal.getsignal(signum) for signum in (signal.SIGINT, signal.SIGTERM)}
    stop = init_with_stop_request([])
    node = Node('spin_until_stopped_test')
    make_executor = rclpy.get_global_executor

    def ctrl_c_while_making_it():
        signal.raise_signal(signal.SIGINT)
        return make_executor()

    monkeypatch.setattr(rclpy, 'get_global_executor', ctrl_c_while_making_it)
    try:
        with pytest.raises(KeyboardInterrupt) as raised:
            spin_until_stopped(node, stop)
        assert raised.traceback[-1].name == 'spin_until_stopped'
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
        for signum, handler in handlers.items():
            signal.signal(signum, handler)


@pytest.fixture
def node():
    context = rclpy.Context()
    rclpy.init(context=context, signal_handler_options=SignalHandlerOptions.NO)
    node = Node('interrupt_between_callbacks_test', context=context)
    executor = SingleThreadedExecutor(context=context)
    executor.add_node(node)
    previous = signal.getsignal(signal.SIGINT)
    yield node, executor
    signal.signal(signal.SIGINT, previous)
    executor.shutdown()
    node.destroy_node()
    rclpy.try_shutdown(context=context)


def test_ctrl_c_leaves_spin_as_keyboard_interrupt_from_a_callback_and_later_ones_are_ignored(node):
    node, executor = node
    ticks = []
    node.create_timer(0.01, lambda: ticks.append(1))

    def not_replaced(signum, frame):
        raise AssertionError('the SIGINT handler was not replaced')

    signal.signal(signal.SIGINT, not_replaced)  # instead of a KeyboardInterrupt that stops pytest
    interrupt_between_callbacks(node)
    executor.spin_once(timeout_sec=1.0)  # a timer callback: Ctrl-C not pressed yet
    assert ticks
    signal.raise_signal(signal.SIGINT)  # the handler only triggers the guard: nothing raised here
    with pytest.raises(KeyboardInterrupt):
        while True:
            executor.spin_once(timeout_sec=1.0)
    assert signal.getsignal(signal.SIGINT) == signal.SIG_IGN
    signal.raise_signal(signal.SIGINT)  # a second Ctrl-C changes nothing: the clean-up may spin
    for _ in range(5):
        executor.spin_once(timeout_sec=0.05)
