"""Regenerate docs/turtlesim/canvas.png: a scripted drawing on a headless turtlesim_node.

Run from the repository root with the environment sourced:
    source env.sh && python docs/turtlesim/draw_canvas.py
It starts turtlesim_node in a private ROS domain, draws with pens, teleports and cmd_vel, then
asks the node's hidden ~/_save_canvas service to write the PNG next to this script.
"""

from __future__ import annotations

import math
import os
import sys
import time
from pathlib import Path

import rclpy
from geometry_msgs.msg import Twist
from owl_common.processes import RosSandbox
from rclpy.node import Node
from std_srvs.srv import Trigger
from turtlesim.msg import Pose
from turtlesim.srv import SetPen, Spawn, TeleportAbsolute

OUTPUT = Path(__file__).resolve().with_name('canvas.png')


class Artist:
    """A node of our own that draws on turtlesim through its services and cmd_vel."""

    def __init__(self, domain_id: int) -> None:
        os.environ['ROS_AUTOMATIC_DISCOVERY_RANGE'] = 'LOCALHOST'  # as the sandbox's processes
        rclpy.init(domain_id=domain_id)
        self.node = Node('turtlesim_artist')

    def close(self) -> None:
        """End the artist's ROS context."""
        rclpy.try_shutdown()

    def call(self, srv_type, name: str, request):
        """The response of one service call; SystemExit when the service is missing or silent."""
        client = self.node.create_client(srv_type, name)
        if not client.wait_for_service(timeout_sec=30.0):
            raise SystemExit(f'{name} did not come up')
        future = client.call_async(request)
        rclpy.spin_until_future_complete(self.node, future, timeout_sec=10.0)
        self.node.destroy_client(client)
        if not future.done():
            raise SystemExit(f'{name} did not answer')
        return future.result()

    def pen(self, turtle: str, rgb: tuple[int, int, int], width: int, off: int = 0) -> None:
        """Set a turtle's pen: colour, width, and off=1 to lift it."""
        r, g, b = rgb
        self.call(SetPen, f'/{turtle}/set_pen', SetPen.Request(r=r, g=g, b=b, width=width, off=off))

    def go(self, turtle: str, x: float, y: float, theta: float = 0.0) -> None:
        """Teleport a turtle there, drawing with its pen on the way."""
        self.call(TeleportAbsolute, f'/{turtle}/teleport_absolute',
                  TeleportAbsolute.Request(x=x, y=y, theta=theta))
        # Teleports are applied at the next 16 ms tick, with the pen of that moment: let it pass
        # before the next pen change.
        time.sleep(0.1)

    def drive(self, turtle: str, linear: float, angular: float, seconds: float) -> None:
        """Hold a velocity command (refreshed inside the 1 s timeout) for `seconds`."""
        publisher = self.node.create_publisher(Twist, f'/{turtle}/cmd_vel', 7)
        poses: list[Pose] = []
        subscription = self.node.create_subscription(Pose, f'/{turtle}/pose', poses.append, 7)
        while publisher.get_subscription_count() == 0 or not poses:
            rclpy.spin_once(self.node, timeout_sec=0.05)
        twist = Twist()
        twist.linear.x, twist.angular.z = linear, angular
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            publisher.publish(twist)
            rclpy.spin_once(self.node, timeout_sec=0.2)
        publisher.publish(Twist())
        self.node.destroy_publisher(publisher)
        self.node.destroy_subscription(subscription)


def draw(artist: Artist) -> None:
    """The picture: a yellow frame, a red star and a white circle."""
    # turtle1: a yellow square frame, pen lifted between moves.
    artist.pen('turtle1', (0, 0, 0), 1, off=1)
    artist.go('turtle1', 1.0, 1.0)
    artist.pen('turtle1', (255, 220, 0), 5)
    for x, y in ((10.0, 1.0), (10.0, 10.0), (1.0, 10.0), (1.0, 1.0)):
        artist.go('turtle1', x, y)
    # A red five-pointed star by turtle2.
    artist.call(Spawn, '/spawn', Spawn.Request(x=5.5, y=8.7, theta=0.0, name=''))
    artist.pen('turtle2', (230, 40, 40), 3)
    for k in range(1, 6):
        angle = math.pi / 2 + k * 4 * math.pi / 5
        artist.go('turtle2', 5.5 + 1.8 * math.cos(angle), 7.0 + 1.8 * math.sin(angle), angle)
    # The course's olive_turtle drives a white circle of radius 1 m.
    artist.call(Spawn, '/spawn', Spawn.Request(x=3.0, y=2.5, theta=0.0, name='olive_turtle'))
    artist.pen('olive_turtle', (255, 255, 255), 3)
    artist.drive('olive_turtle', 2.0, 2.0, math.pi)
    # turtle1 ends up in the middle, facing north-east.
    artist.pen('turtle1', (0, 0, 0), 1, off=1)
    artist.go('turtle1', 5.5, 4.0, math.pi / 4)


def main() -> int:
    """Draw on a headless turtlesim_node and save its canvas as canvas.png; the exit code."""
    with RosSandbox() as sandbox:
        sim = sandbox.run('turtlesim', 'turtlesim_node', '--headless', '--canvas-png', str(OUTPUT))
        sim.wait_for(r'Spawning turtle \[turtle1\]', timeout=30)
        artist = Artist(sandbox.domain_id)
        try:
            draw(artist)
            time.sleep(0.2)  # a few ticks, so the last teleport is applied
            response = artist.call(Trigger, '/turtlesim/_save_canvas', Trigger.Request())
        finally:
            artist.close()
    print(response.message if response.success else f'error: {response.message}')
    return 0 if response.success else 1


if __name__ == '__main__':
    sys.exit(main())
