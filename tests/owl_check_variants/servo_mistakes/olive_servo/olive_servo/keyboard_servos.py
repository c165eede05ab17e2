"""keyboard_servos without bounds on its goals: owl check must fail it."""

import pygame
import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.signals import SignalHandlerOptions
from std_msgs.msg import Float32


class KeyboardServos(Node):
    def __init__(self):
        super().__init__('keyboard_servos')
        pygame.init()
        self.screen = pygame.display.set_mode((300, 200))
        self.pan_publisher = self.create_publisher(Float32, '/olive/servo/pan/goal/position', 10)
        self.tilt_publisher = self.create_publisher(Float32, '/olive/servo/tilt/goal/position', 10)
        self.pan = 0.0
        self.tilt = 0.0
        self.timer = self.create_timer(0.01, self.publish_goals)

    def publish_goals(self):
        pygame.event.pump()
        keys = pygame.key.get_pressed()
        if keys[pygame.K_LEFT]:
            self.pan += 0.01
        if keys[pygame.K_RIGHT]:
            self.pan -= 0.01
        if keys[pygame.K_UP]:
            self.tilt -= 0.01
        if keys[pygame.K_DOWN]:
            self.tilt += 0.01
        self.pan_publisher.publish(Float32(data=self.pan))
        self.tilt_publisher.publish(Float32(data=self.tilt))


def main(args=None):
    rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)
    node = KeyboardServos()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    node.destroy_node()
    rclpy.try_shutdown()
