"""The servos' torque switch: their setTorqueEnable and setTorqueDisable Trigger services."""

import time
from collections.abc import Sequence

from rclpy.client import Client
from rclpy.duration import Duration
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from std_srvs.srv import Trigger

ANSWER_TIMEOUT = 5.0    # s for a servo to answer a torque request before it is asked again
# At shutdown, all of it within the 5 s that ros2 launch waits before it escalates to SIGTERM: first
# up to GOALS_ARRIVED_TIMEOUT s for the servos to have every goal sent, then DISABLE_TIMEOUT s for
# their answers (a loaded machine answered after more than 2 s).
GOALS_ARRIVED_TIMEOUT = 0.5  # s
DISABLE_TIMEOUT = 3.5  # s
WAITING_EVERY = 5.0     # s between two "waiting for service" lines


class TorqueError(RuntimeError):
    """A servo refused to enable its torque."""


class ServoTorque:
    """Enables the torque of some servos before their first goal and disables it at the end.

    The servo ignores goals while its torque is off (a safety feature, section 4.4).
    """

    def __init__(self, node: Node, servos: Sequence[str]) -> None:
        self.node = node
        self.enable_clients = {
            servo: node.create_client(Trigger, f'/olive/servo/{servo}/setTorqueEnable') for servo in servos}
        self.disable_clients = {
            servo: node.create_client(Trigger, f'/olive/servo/{servo}/setTorqueDisable') for servo in servos}
        self.enabled: list[str] = []

    def enable(self) -> None:
        """Wait for the services, then enable every servo's torque; TorqueError if one refuses.

        A servo that does not answer within ANSWER_TIMEOUT is asked again, as long as it takes:
        a kit started at the same moment as this node, on a busy machine, took 11 s to answer.
        """
        for client in self.enable_clients.values():
            while not client.wait_for_service(timeout_sec=1.0):
                self.node.get_logger().info(
                    f'waiting for service {client.srv_name}', throttle_duration_sec=WAITING_EVERY)
        unanswered = dict(self.enable_clients)
        while unanswered:
            for servo, response in self._call(unanswered, ANSWER_TIMEOUT).items():
                service = self.enable_clients[servo].srv_name
                if response is None:
                    self.node.get_logger().warning(
                        f'{service} did not answer within {ANSWER_TIMEOUT} s: asking again')
                    continue
                if not response.success:
                    raise TorqueError(f'{service} refused: {response.message}')
                del unanswered[servo]
                self.enabled.append(servo)
        self.enabled.sort(key=list(self.enable_clients).index)
        self.node.get_logger().info(f"torque enabled: {', '.join(self.enabled)}")

    def disable(self) -> None:
        """Disable the torque this node enabled; warn about a servo that does not answer.

        First the servos get every goal this node sent them: DDS keeps a topic's messages in order,
        not a topic's against a service's, so on a busy machine a goal sent just before could reach
        a servo after its torque went off, and the servo warns that it ignored it.
        """
        goals_sent_by = time.monotonic() + GOALS_ARRIVED_TIMEOUT
        for publisher in self.node.publishers:
            if any(publisher.topic_name.startswith(f'/olive/servo/{servo}/') for servo in self.enabled):
                publisher.wait_for_all_acked(Duration(seconds=max(0.0, goals_sent_by - time.monotonic())))
        clients = {servo: self.disable_clients[servo] for servo in self.enabled}
        for servo, response in self._call(clients, DISABLE_TIMEOUT).items():
            if response is not None and response.success:
                self.node.get_logger().info(f'torque disabled: {servo}')
            else:
                reason = response.message if response is not None else f'no answer within {DISABLE_TIMEOUT} s'
                self.node.get_logger().warning(
                    f'{clients[servo].srv_name} failed ({reason}): the torque may still be on')
        self.enabled.clear()

    def _call(self, clients: dict[str, Client], timeout: float) -> dict[str, Trigger.Response | None]:
        """Call every client at once; each one's response, or None if it did not come in time.

        The answers are waited for in an executor of their own: the one the node spun in may still
        hold callbacks made ready before Ctrl-C (an image that leads to a goal), which would run
        here and send a goal after the torque request (seen in suite runs: the servo warned that it
        ignored it). A fresh executor waits only on what the node has now.
        """
        futures = {servo: client.call_async(Trigger.Request()) for servo, client in clients.items()}
        deadline = time.monotonic() + timeout
        executor = SingleThreadedExecutor(context=self.node.context)
        executor.add_node(self.node)
        try:
            # Short waits: with rclpy's Ctrl-C handler off, Ctrl-C is only seen when a wait returns.
            while not all(f.done() for f in futures.values()) and time.monotonic() < deadline:
                executor.spin_once(timeout_sec=0.1)
        finally:
            executor.remove_node(self.node)
            executor.shutdown()
        return {servo: future.result() if future.done() else None for servo, future in futures.items()}
