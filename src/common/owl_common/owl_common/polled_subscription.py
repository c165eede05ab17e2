"""Subscriptions that the executor never wakes up for: their owner takes the messages when it needs them."""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

from rclpy.callback_groups import CallbackGroup
from rclpy.node import Node
from rclpy.qos import QoSProfile


class _PolledGroup(CallbackGroup):
    """The executor never waits on its entities: their owner takes from them.

    That includes the subscription's QoS event handlers (so no incompatible-QoS warning for it):
    they share the reader's status condition, and while a message waits to be taken they woke the
    executor over and over.
    """

    def can_execute(self, entity: Any) -> bool:
        return False

    def beginning_execution(self, entity: Any) -> bool:
        return False

    def ending_execution(self, entity: Any) -> None:
        pass


class PolledSubscription:
    """A subscription whose messages are handed to `callback` only when poll() is called.

    For inputs that matter only at the moment an output is made (the camera's view of the servo
    joints): every executor wake-up costs the node's whole wait set, which at 100 Hz per servo was
    the largest part of the camera's CPU after the rendering. poll() may be called from any thread.
    With raw=True the callback gets the serialized bytes, as with rclpy's raw subscriptions; with
    info=True it also gets the message's info from DDS (a dict: 'source_timestamp', when it was
    sent, in ns since the epoch; 'received_timestamp'; ...).
    """

    def __init__(self, node: Node, msg_type: type, topic: str, callback: Callable[..., None],
                 qos: QoSProfile | int, raw: bool = False, info: bool = False) -> None:
        self._subscription = node.create_subscription(msg_type, topic, callback, qos,
                                                      callback_group=_PolledGroup(), raw=raw)
        self._lock = threading.Lock()
        self._info = info

    def poll(self) -> None:
        """Pass every message received since the last poll to the callback, oldest first."""
        subscription = self._subscription
        with self._lock, subscription.handle:
            while (taken := subscription.handle.take_message(subscription.msg_type,
                                                             subscription.raw)) is not None:
                subscription.callback(*taken) if self._info else subscription.callback(taken[0])
