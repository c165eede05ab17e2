"""Appendix 5.3 "Code PID testing": the pan servo's goal alternates between 0.0 and 1.57 rad every 3 s.

The course's listing with its fixes, each marked "Fix:" (see this package's README).
"""

import signal

import rclpy
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
    rclpy.init(args=args)
    cntrl_publisher = None

    try:
        cntrl_publisher = PidTesting()
        cntrl_publisher.enable_torque()
        rclpy.spin(cntrl_publisher)
    except KeyboardInterrupt:
        pass
    finally:
        # Fix: the listing cleans up only after Ctrl-C, and not at all for a Ctrl-C while the
        # node waits for the servo; here a second Ctrl-C cannot interrupt the clean-up either.
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        if cntrl_publisher is not None:
            cntrl_publisher.disable_torque()
            cntrl_publisher.destroy_node()
        rclpy.shutdown()


if __name__ == "__main__":
    main()
