"""A node of the calling process in another ROS domain, spun on a background thread.

The system tests watch and drive their processes through it, and so does `make demo`.
"""

from __future__ import annotations

import threading
from typing import Any

import rclpy
from rclpy.context import Context
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from rclpy.qos import QoSProfile


class Probe:
    """An rclpy node in the given domain; callbacks run on the probe's own thread."""

    def __init__(self, domain_id: int, name: str = 'owl_probe') -> None:
        self.context = Context()
        rclpy.init(context=self.context, domain_id=domain_id)
        self.node = Node(name, context=self.context)
        self.executor = SingleThreadedExecutor(context=self.context)
        self.executor.add_node(self.node)
        self._thread = threading.Thread(target=self._spin, daemon=True)
        self._thread.start()

    def _spin(self) -> None:
        try:
            self.executor.spin()
        except Exception:  # the context shut down under it: the probe is closing
            pass

    def close(self) -> None:
        """Stop spinning and leave the domain: the node, the context and the spin thread end."""
        self.executor.shutdown(timeout_sec=1.0)
        self.node.destroy_node()
        rclpy.try_shutdown(context=self.context)
        self._thread.join(2.0)

    def collect(self, msg_type: Any, topic: str, qos: QoSProfile | int = 10) -> list[Any]:
        """Subscribe now; the returned list fills with every message received from then on."""
        received: list[Any] = []
        self.node.create_subscription(msg_type, topic, received.append, qos)
        return received

    def collect_with_info(self, msg_type: Any, topic: str, field: str,
                          qos: QoSProfile | int = 10) -> list[tuple[int, Any]]:
        """As collect, each message with one field of the message info DDS gave with it.

        'publication_sequence_number' tells which of the publisher's messages this is (its first is 1),
        even when the probe missed the first ones: a subscription made just before a publisher starts
        may match it late. 'source_timestamp' is when the publisher sent it (ns since the epoch): a rate
        measured from these is the publisher's, however late a busy machine lets the probe take the
        messages (a backlog taken at once made a 10 Hz publisher look 13.6 Hz).
        """
        received: list[tuple[int, Any]] = []

        def with_info(msg: Any, info: dict[str, Any]) -> None:
            received.append((info[field], msg))

        # rclpy passes the message info to a two-argument callback; its annotation names only one.
        self.node.create_subscription(msg_type, topic, with_info, qos)  # type: ignore[arg-type]
        return received
