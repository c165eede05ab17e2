"""Section 4.4.1 project "Keyboard Control Servos": the arrow keys move the pan and tilt servos.

Left/Right turn the lower (pan) servo, Up/Down the upper (tilt) servo, while the key is held, at
`speed` rad/s and within the bounds; the keys are read from this node's pygame window.
"""

import os
import signal
import sys
import time

# pygame greets with two lines on stdout when imported; this node's output stays its own (a bad
# parameter is one line). A student's script may keep the greeting.
os.environ.setdefault('PYGAME_HIDE_SUPPORT_PROMPT', '1')
# SDL would take over SIGTERM and turn it into a window-close event, which nobody reads while the
# node waits for the servos: `kill` would do nothing then. SIGTERM stays Python's, as in our other nodes.
os.environ.setdefault('SDL_NO_SIGNAL_HANDLERS', '1')

import pygame
import rclpy
from rcl_interfaces.msg import FloatingPointRange, ParameterDescriptor
from rclpy.exceptions import ParameterException
from rclpy.node import Node
from rclpy.timer import Timer
from std_msgs.msg import Float32

from olive_servo.bound_parameters import BoundParameters
from olive_servo.goals import KeyboardGoals
from olive_servo.torque import ServoTorque, TorqueError

SERVOS = ('pan', 'tilt')
PUBLISH_PERIOD = 0.01  # s, the course's timer
SPEED_RANGE = (0.05, 6.0)  # rad/s; 6 rad/s is about the servo's own top speed
KEY_NAMES = {pygame.K_LEFT: 'left', pygame.K_RIGHT: 'right', pygame.K_UP: 'up', pygame.K_DOWN: 'down'}
WINDOW_SIZE = (420, 130)
HELP = ('Left/Right: turn the head (pan)', 'Up/Down: look up/down (tilt)',
        'Ctrl-C in the terminal that started it stops it')  # a window in a browser has no close box


class WindowClosed(Exception):
    """The user closed the node's window: stop as at Ctrl-C."""


class KeyboardServos(Node):

    def __init__(self) -> None:
        super().__init__('keyboard_servos')
        self.declare_parameter('speed', 1.0, ParameterDescriptor(
            description='How fast a held arrow key moves its servo\'s goal, rad/s.',
            floating_point_range=[FloatingPointRange(from_value=SPEED_RANGE[0], to_value=SPEED_RANGE[1])]))
        self.bounds = BoundParameters(self, SERVOS)  # pan_min .. tilt_max, each pair checked
        self.torque = ServoTorque(self, SERVOS)
        self.publishers_ = {servo: self.create_publisher(Float32, f'/olive/servo/{servo}/goal/position', 10)
                            for servo in SERVOS}
        self.goals = KeyboardGoals()
        self.held: set[str] = set()  # names of the arrow keys held down now
        self.last_step = time.monotonic()
        self.timer: Timer | None = None  # created once the torque is on: the servos ignore goals before

        # pygame reads the keyboard through a window of its own: keys count while it has the focus.
        # Only the display and fonts: pygame.init() would also open the sound card, which a machine
        # without one answers with a dozen ALSA error lines.
        pygame.display.init()
        pygame.font.init()
        self.screen = pygame.display.set_mode(WINDOW_SIZE)
        pygame.display.set_caption('keyboard_servos')
        self.font = pygame.font.Font(None, 24)
        self.shown = ''  # the status line the window shows, to redraw only when it changes
        self.show('waiting for the servos to switch their torque on')

    def enable_torque(self) -> None:
        self.torque.enable()
        speed = self.get_parameter('speed').value
        self.get_logger().info(f"keys in the 'keyboard_servos' window move the head at {speed} rad/s: "
                               'Left/Right turn it (pan), Up/Down tilt the camera')
        self.last_step = time.monotonic()
        self.timer = self.create_timer(PUBLISH_PERIOD, self.publish_goals)

    def disable_torque(self) -> None:
        if self.timer is not None:
            self.timer.cancel()  # no goal may follow the torque requests
        self.torque.disable()

    def read_keys(self) -> None:
        for event in pygame.event.get():
            if event.type == pygame.KEYDOWN and event.key in KEY_NAMES:
                self.held.add(KEY_NAMES[event.key])
            elif event.type == pygame.KEYUP and event.key in KEY_NAMES:
                self.held.discard(KEY_NAMES[event.key])
            elif event.type == pygame.QUIT:
                raise WindowClosed

    def publish_goals(self) -> None:
        self.read_keys()
        now = time.monotonic()
        goals = self.goals.advance(self.held, self.get_parameter('speed').value, now - self.last_step,
                                   self.bounds.all())
        self.last_step = now
        for servo in SERVOS:
            msg = Float32()
            msg.data = goals[servo]
            self.publishers_[servo].publish(msg)
        self.show(f"goals: pan {goals['pan']:+.2f} rad, tilt {goals['tilt']:+.2f} rad")

    def show(self, status: str) -> None:
        """Draw the keys' help and a status line in the window, when the status changed."""
        if status == self.shown:
            return
        self.shown = status
        self.screen.fill((30, 30, 30))
        for row, text in enumerate((*HELP, status)):
            self.screen.blit(self.font.render(text, True, (230, 230, 230)), (12, 10 + 28 * row))
        pygame.display.flip()

    def destroy_node(self) -> None:
        pygame.quit()  # closes the window
        super().destroy_node()


def main(args: list[str] | None = None) -> None:
    rclpy.init(args=args)
    keyboard_servos = None
    try:
        keyboard_servos = KeyboardServos()
        keyboard_servos.enable_torque()
        rclpy.spin(keyboard_servos)
    except (KeyboardInterrupt, WindowClosed):
        pass  # Ctrl-C is how the course stops a node; closing the window too
    except TorqueError as error:
        assert keyboard_servos is not None  # only enable_torque() raises it
        keyboard_servos.get_logger().error(str(error))
        sys.exit(1)
    except (ParameterException, ValueError) as error:
        if keyboard_servos is not None:
            raise
        print(f'keyboard_servos: error: {error}', file=sys.stderr)  # a bad --ros-args parameter
        sys.exit(2)
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C must not stop the clean-up
        if keyboard_servos is not None:
            keyboard_servos.disable_torque()
            keyboard_servos.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
