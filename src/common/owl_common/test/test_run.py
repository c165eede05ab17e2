import signal

import pytest
import rclpy
from owl_common.run import (
    StopRequest,
    init_with_stop_request,
    spin_until_stopped,
)
from rclpy.node import Node
from std_msgs.msg import Bool


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


def test_with_events_the_loop_runs_timers_and_subscriptions_and_a_stop_ends_it_with_the_nodes_whole():
    handlers = {signum: signal.getsignal(signum) for signum in (signal.SIGINT, signal.SIGTERM)}
    stop = init_with_stop_request([])
    node = Node('spin_until_stopped_events_test')
    heard = []
    publisher = node.create_publisher(Bool, 'spin_until_stopped_events_test', 10)
    node.create_subscription(Bool, 'spin_until_stopped_events_test', heard.append, 10)

    def publish_until_heard_then_stop():
        if heard:
            signal.raise_signal(signal.SIGINT)
        else:
            publisher.publish(Bool(data=True))

    node.create_timer(0.02, publish_until_heard_then_stop)
    try:
        with pytest.raises(KeyboardInterrupt):
            spin_until_stopped(node, stop, events=True)
        assert heard
        assert stop.requested
        assert rclpy.ok(), 'the stop shut ROS down before the nodes could clean up'
        publisher.publish(Bool(data=False))  # the node still works for its own clean-up
    finally:
        node.destroy_node()
        rclpy.try_shutdown()
        for signum, handler in handlers.items():
            signal.signal(signum, handler)
