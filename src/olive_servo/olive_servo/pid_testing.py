"""Appendix 5.3 "Code PID testing": the pan servo's goal alternates between 0.0 and 1.57 rad every 3 s.

The course's listing with its fixes, each marked "Fix:" (see this package's README).
"""

import rclpy
from owl_common.run import begin_cleanup, init_with_stop_request, spin_until_stopped
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from std_msgs.msg import Float32
from std_srvs.srv import Trigger

# Fix: the printed listing waits for the torque-off answer forever; a servo that is gone
# would hang the Ctrl-C.
DISABLE_TIMEOUT = 2.0  # s


class PidTesting(Node):

    def __init__(self) -> None:
        # Changed: the listing names its node control_servo, the name of the project's own node.
        super().__init__("pid_testing")
        self.service_enable_torque = self.create_client(Trigger,
                                                        "/olive/servo/pan/setTorqueEnable")
        self.service_disable_torque = self.create_client(Trigger,
                                                         "/olive/servo/pan/setTorqueDisable")
        while not self.service_enable_torque.wait_for_service(timeout_sec=1.0):
            self.get_logger().info("service not available")
        while not self.service_disable_torque.wait_for_service(timeout_sec=1.0):
            self.get_logger().info("service not available")
        self.request_enable_torque = Trigger.Request()
        self.request_disable_torque = Trigger.Request()
        self.topic_gp = "/olive/servo/pan/goal/position"
        self.publisher = self.create_publisher(Float32, self.topic_gp, 10)
        self.timer = self.create_timer(3.0, self.publish_goal)
        self.state = True

    def enable_torque(self) -> None:
        self.future = self.service_enable_torque.call_async(self.request_enable_torque)
        rclpy.spin_until_future_complete(self, self.future)

    def disable_torque(self) -> None:
        self.timer.cancel()  # Fix: no goal after the torque is off
        self.future = self.service_disable_torque.call_async(self.request_disable_torque)
        rclpy.spin_until_future_complete(self, self.future, timeout_sec=DISABLE_TIMEOUT)

    def publish_goal(self) -> None:
        msg = Float32()

        if self.state:  # Changed: the listing compares `== True`, which ruff (E712) flags
            msg.data = 1.57
            self.state = False
        else:
            msg.data = 0.0
            self.state = True

        # Fix: in the printed listing this line fell outside the method at a page break.
        self.publisher.publish(msg)


def main(args: list[str] | None = None) -> None:
    # Fix: rclpy.init installs rclpy's Ctrl-C handler, which shuts ROS down before the except
    # clause runs: the listing's disable_torque() cannot wait for its answer, and its
    # rclpy.shutdown() then fails with a traceback. Here Ctrl-C is a stop request that
    # spin_until_stopped (rclpy.spin) raises as KeyboardInterrupt, and ROS still works for the
    # clean-up (owl_common.run says more).
    stop = init_with_stop_request(args)
    cntrl_publisher = None

    try:
        cntrl_publisher = PidTesting()
        cntrl_publisher.enable_torque()
        spin_until_stopped(cntrl_publisher, stop)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    finally:
        # Fix: the listing cleans up only after Ctrl-C, and not at all for a Ctrl-C while the
        # node waits for the servo; here it also ignores a second Ctrl-C.
        begin_cleanup()
        if cntrl_publisher is not None:
            cntrl_publisher.disable_torque()
            cntrl_publisher.destroy_node()
        rclpy.try_shutdown()


if __name__ == "__main__":
    main()
