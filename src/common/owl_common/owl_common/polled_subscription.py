"""Subscriptions that no executor ever sees: their owner takes the messages when it needs them."""

from __future__ import annotations

import threading
from collections.abc import Callable

from rclpy.impl.implementation_singleton import rclpy_implementation as _rclpy
from rclpy.node import Node
from rclpy.qos import QoSProfile
from rclpy.type_support import check_is_valid_msg_type
from rclpy.validate_topic_name import validate_topic_name


class PolledSubscription:
    """A subscription whose messages are handed to `callback` only when poll() is called.

    For inputs that matter only at the moment an output is made (the camera's view of the servo
    joints, the goals robot_view plots): waking an executor for each of them, at 100 Hz per servo,
    was the largest part of the camera's CPU after the rendering. The subscription is a bare rcl
    one, in none of the node's lists, so no executor takes from it: rclpy's EventsExecutor, which
    spin_node may use, would ignore a callback group that tried to keep it away, and it has no QoS
    event handlers (they woke the executor while a message waited to be taken). poll() may be
    called from any thread. With raw=True the callback gets the serialized bytes; with info=True it
    also gets the message's info from DDS (a dict: 'source_timestamp', when it was sent, in ns since
    the epoch; 'received_timestamp'; ...). destroy() ends it; its node's destroy_node does not.
    """

    def __init__(self, node: Node, msg_type: type, topic: str, callback: Callable[..., None],
                 qos: QoSProfile | int, raw: bool = False, info: bool = False) -> None:
        check_is_valid_msg_type(msg_type)
        try:
            node.resolve_topic_name(topic)
        except RuntimeError:  # say what is wrong with the name, as create_subscription does
            validate_topic_name(topic)
            raise
        profile = qos if isinstance(qos, QoSProfile) else QoSProfile(depth=qos)
        with node.handle:
            self._handle = _rclpy.Subscription(node.handle, msg_type, topic, profile.get_c_qos_profile())
        self._msg_type = msg_type
        self._callback = callback
        self._raw = raw
        self._info = info
        self._lock = threading.Lock()
        self._destroyed = False

    def poll(self) -> None:
        """Pass every message received since the last poll to the callback, oldest first."""
        with self._lock:
            if self._destroyed:
                return
            with self._handle:
                while (taken := self._handle.take_message(self._msg_type, self._raw)) is not None:
                    self._callback(*taken) if self._info else self._callback(taken[0])

    def destroy(self) -> None:
        """End the subscription (once a poll running elsewhere is done); later polls do nothing."""
        with self._lock:
            if not self._destroyed:
                self._destroyed = True
                self._handle.destroy_when_not_in_use()
