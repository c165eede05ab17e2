"""turtlesim_node: the node `turtlesim`, a 500 x 500 px pond of turtles driven over ROS.

The 16 ms tick runs on a thread of its own and ROS callbacks on the executor's thread, each
under one lock, so, as upstream, a callback never overlaps a physics step. A tick on an executor
timer cost a wake-up of the executor's whole wait set (every turtle's services, action server and
QoS event handlers), three quarters of the node's CPU with 20 turtles. Per-tick logic lives in
turtle.py, drawing in canvas.py.
"""

from __future__ import annotations

import argparse
import functools
import math
import os
import random
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any, TypeVar

import rclpy
from geometry_msgs.msg import Twist
from owl_common.periodic import PeriodicThread
from owl_common.run import spin_node
from PIL import Image
from rcl_interfaces.msg import IntegerRange, ParameterDescriptor, ParameterEvent
from rclpy.action import ActionServer, CancelResponse, GoalResponse
from rclpy.action.server import ServerGoalHandle
from rclpy.logging import LoggingSeverity
from rclpy.node import Node
from rclpy.publisher import Publisher
from rclpy.qos import HistoryPolicy, QoSProfile, ReliabilityPolicy
from rclpy.service import Service
from rclpy.subscription import Subscription
from rclpy.task import Future
from rclpy.utilities import remove_ros_args
from sensor_msgs.msg import CompressedImage
from std_srvs.srv import Empty, Trigger
from turtlesim.action import RotateAbsolute
from turtlesim.msg import Color
from turtlesim.msg import Pose as PoseMsg
from turtlesim.srv import Kill, SetPen, Spawn, TeleportAbsolute, TeleportRelative

from turtlesim_py import world
from turtlesim_py.arrow_keys import held_drive
from turtlesim_py.browser_window import BrowserWindow
from turtlesim_py.canvas import DEFAULT_BACKGROUND, SHELL_COLORS, Canvas, SpriteView, encode_png
from turtlesim_py.rclcpp_parameters import declare_parameter_events_qos
from turtlesim_py.turtle import RotationGoal, TickResult, Turtle

if TYPE_CHECKING:
    from turtlesim_py.window import CanvasWindow

# Humble: keep last 7, otherwise the defaults (reliable, volatile).
TOPIC_QOS = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=7)
PARAMETER_EVENTS_QOS = QoSProfile(depth=100, reliability=ReliabilityPolicy.BEST_EFFORT)
IMAGE_PERIOD = 0.1  # s between CompressedImage messages, when they are enabled
WINDOW_PERIOD = 0.03  # s between window repaints: every other tick, plenty for the eye

Callback = TypeVar('Callback', bound=Callable[..., Any])


def background_descriptor(channel: str) -> ParameterDescriptor:
    """The descriptor of a background_r/g/b parameter: an integer 0..255."""
    return ParameterDescriptor(
        description=f'{channel} channel of the background color',
        integer_range=[IntegerRange(from_value=0, to_value=255, step=1)])


def non_finite(**values: float) -> str | None:
    """None when every value is finite, else 'name=value, ...' for the error log.

    Upstream would carry a NaN into the pose for good; we refuse such requests instead.
    """
    if all(math.isfinite(v) for v in values.values()):
        return None
    return ', '.join(f'{name}={value}' for name, value in values.items())


class GoalOfHandle(RotationGoal):
    """A rotation goal bound to its rclpy goal handle; `done` resolves with the result."""

    def __init__(self, handle: ServerGoalHandle, wake: Callable[[], None]) -> None:
        super().__init__(handle.request.theta)
        self.handle = handle
        self.done = Future()
        self._wake = wake

    def cancel_requested(self) -> bool:
        """Whether the action client asked to cancel the goal."""
        return self.handle.is_cancel_requested

    def publish_feedback(self, remaining: float) -> None:
        """Send the remaining angle (rad) to the action client as feedback."""
        self.handle.publish_feedback(RotateAbsolute.Feedback(remaining=remaining))

    def finish(self, status: str, delta: float) -> None:
        """End the goal handle with status and resolve `done` with the rotated delta (rad)."""
        {'succeeded': self.handle.succeed, 'canceled': self.handle.canceled,
         'aborted': self.handle.abort}[status]()
        self.done.set_result(RotateAbsolute.Result(delta=delta))
        self._wake()  # the executor resumes the goal's execute callback only when it wakes up


class TurtleEndpoints:
    """The topics, services and action server of one turtle, all under `<name>/`."""

    def __init__(self, node: TurtlesimNode, turtle: Turtle) -> None:
        self.turtle = turtle
        self._node = node
        self._entities: list[Publisher | Subscription | Service | ActionServer] = []
        self._goals: dict[bytes, GoalOfHandle] = {}
        self._pose, self._color = PoseMsg(), Color()
        name = turtle.name
        locked = node.between_ticks
        try:
            self.pose_pub = node.create_publisher(PoseMsg, f'{name}/pose', TOPIC_QOS)
            self._entities.append(self.pose_pub)
            self.color_pub = node.create_publisher(Color, f'{name}/color_sensor', TOPIC_QOS)
            self._entities.append(self.color_pub)
            self._entities += [
                node.create_subscription(Twist, f'{name}/cmd_vel', locked(self._on_cmd_vel), TOPIC_QOS),
                node.create_service(SetPen, f'{name}/set_pen', locked(self._on_set_pen)),
                node.create_service(
                    TeleportAbsolute, f'{name}/teleport_absolute', locked(self._on_teleport_absolute)),
                node.create_service(
                    TeleportRelative, f'{name}/teleport_relative', locked(self._on_teleport_relative)),
                ActionServer(
                    node, RotateAbsolute, f'{name}/rotate_absolute',
                    execute_callback=self._execute_goal,
                    goal_callback=self._on_goal_request,
                    handle_accepted_callback=locked(self._on_goal_accepted),
                    cancel_callback=lambda _handle: CancelResponse.ACCEPT),
            ]
        except BaseException:
            self.destroy()
            raise

    def destroy(self) -> None:
        """Abort the turtle's goal and destroy its endpoints, newest first: the turtle leaves ROS."""
        self.turtle.abort_goal()
        for entity in reversed(self._entities):
            if isinstance(entity, ActionServer):
                entity.destroy()
            elif isinstance(entity, Publisher):
                self._node.destroy_publisher(entity)
            elif isinstance(entity, Subscription):
                self._node.destroy_subscription(entity)
            else:
                self._node.destroy_service(entity)
        self._entities.clear()

    def publish(self, result: TickResult) -> None:
        """Publish one tick's pose and colour-sensor reading."""
        pose, color = self._pose, self._color  # reused: building messages costs more than filling them
        p = result.pose
        pose.x, pose.y, pose.theta = p.x, p.y, p.theta
        pose.linear_velocity, pose.angular_velocity = p.linear_velocity, p.angular_velocity
        color.r, color.g, color.b = result.color
        self.pose_pub.publish(pose)
        self.color_pub.publish(color)

    def _on_cmd_vel(self, msg: Twist) -> None:
        if self._refused('velocity command', **{
                'linear.x': msg.linear.x, 'linear.y': msg.linear.y, 'angular.z': msg.angular.z}):
            return
        self.turtle.command_velocity(msg.linear.x, msg.linear.y, msg.angular.z, now=self._node.now())

    def _on_set_pen(self, request: SetPen.Request, response: SetPen.Response) -> SetPen.Response:
        self.turtle.set_pen(request.r, request.g, request.b, request.width, request.off)
        return response

    def _on_teleport_absolute(self, request: TeleportAbsolute.Request,
                              response: TeleportAbsolute.Response) -> TeleportAbsolute.Response:
        if not self._refused('teleport_absolute', x=request.x, y=request.y, theta=request.theta):
            self.turtle.teleport_absolute(request.x, request.y, request.theta)
        return response

    def _on_teleport_relative(self, request: TeleportRelative.Request,
                              response: TeleportRelative.Response) -> TeleportRelative.Response:
        if not self._refused('teleport_relative', linear=request.linear, angular=request.angular):
            self.turtle.teleport_relative(request.linear, request.angular)
        return response

    def _refused(self, what: str, **values: float) -> bool:
        """True (and an error logged) when a request carries NaN or infinity."""
        shown = non_finite(**values)
        if shown is not None:
            self._node.get_logger().error(
                f'Refusing {what} for turtle [{self.turtle.name}]: every value must be finite ({shown})')
        return shown is not None

    def _on_goal_request(self, goal: RotateAbsolute.Goal) -> GoalResponse:
        # Upstream accepts any goal, but a NaN heading is never reached: the turtle would spin on.
        if self._refused('rotation goal', theta=goal.theta):
            return GoalResponse.REJECT
        return GoalResponse.ACCEPT

    def _on_goal_accepted(self, handle: ServerGoalHandle) -> None:
        goal = GoalOfHandle(handle, self._node.wake_executor)
        self._goals[bytes(handle.goal_id.uuid)] = goal
        handle.execute()  # EXECUTING now, so the next tick may finish it
        self.turtle.start_rotation(goal)

    async def _execute_goal(self, handle: ServerGoalHandle) -> RotateAbsolute.Result:
        goal = self._goals.pop(bytes(handle.goal_id.uuid))
        return await goal.done


class TurtlesimNode(Node):
    """Node `turtlesim`: the pond, its turtles' endpoints, and the 16 ms tick that moves them.

    canvas_png is where the hidden ~/_save_canvas service writes the canvas; publish_image sends frames on
    ~/canvas/compressed; window opens a Tk window when there is a display, else the browser window
    (browser_window.py) that `owl windows` shows, whose held arrow keys drive turtle1.
    """

    def __init__(self, canvas_png: Path = Path('turtlesim.png'), publish_image: bool = False,
                 window: bool = False) -> None:
        # Set first: rclpy destroys a half-built node (bad --ros-args parameter) via destroy_node().
        self.window: CanvasWindow | BrowserWindow | None = None
        self._ticks: PeriodicThread | None = None
        self._tick_lock = threading.RLock()  # held by the tick and by every ROS callback
        super().__init__('turtlesim')
        for channel, default in zip(('red', 'green', 'blue'), DEFAULT_BACKGROUND, strict=True):
            name = f'background_{channel[0]}'
            self.declare_parameter(name, default, background_descriptor(channel.capitalize()))
        declare_parameter_events_qos(self)
        self.canvas = Canvas()
        self.canvas_png = canvas_png
        self.turtles: dict[str, TurtleEndpoints] = {}
        self._spawn_counter = 0
        self._random = random.Random(time.time())
        self._last_tick: float | None = None
        self._stale: set[str] = set()  # frame consumers ('window', 'image') owed a new frame
        self._last_frame = {'window': -math.inf, 'image': -math.inf}

        locked = self.between_ticks
        self.create_subscription(ParameterEvent, '/parameter_events', locked(self._on_parameter_event),
                                 PARAMETER_EVENTS_QOS)
        self.create_service(Empty, 'clear', locked(self._on_clear))
        self.create_service(Empty, 'reset', locked(self._on_reset))
        self.create_service(Spawn, 'spawn', locked(self._on_spawn))
        self.create_service(Kill, 'kill', locked(self._on_kill))
        # Hidden (leading underscore), so `ros2 service list` looks exactly like upstream's.
        self.create_service(Trigger, '~/_save_canvas', locked(self._on_save_canvas))
        self._image_pub = None
        if publish_image:
            self._image_pub = self.create_publisher(CompressedImage, '~/canvas/compressed', 1)

        self.get_logger().info(f'Starting turtlesim with node name {self.get_fully_qualified_name()}')
        self.spawn_turtle('', world.CENTER, world.CENTER, 0.0)
        # Tk must be used from one thread only: the tick's, which opens, pumps and closes it.
        self._window_wanted = window
        if self._window_wanted:
            # Closing the window shuts ROS down from the executor's thread, not from the tick's.
            self._window_closed = self.create_guard_condition(self._on_window_closed)
        self._ticks = PeriodicThread(1.0 / world.TICK_DT, self._tick, 'turtlesim.tick', self.context.ok,
                                     finish=self._close_window, catch_up=world.TICK_CATCH_UP)

    def between_ticks(self, callback: Callback) -> Callback:
        """callback, made to run under the tick lock (never during a tick)."""
        @functools.wraps(callback)  # keeps the signature rclpy inspects
        def locked(*args: Any) -> Any:
            with self._tick_lock:
                return callback(*args)
        return locked  # type: ignore[return-value]

    def wake_executor(self) -> None:
        """Make the executor look at its tasks again (from any thread)."""
        executor = self.executor
        if executor is not None:
            executor.wake()

    def _open_window(self) -> None:
        display = os.environ.get('DISPLAY') and os.environ.get('OWL_HEADLESS') != '1'
        problem = self._open_tk_window() if display else None
        if self.window is None:
            self.window = BrowserWindow.open()
            if self.window is not None:
                self.get_logger().info(
                    f"No display{f' ({problem})' if problem else ''}: the TurtleSim window is shown in a "
                    "browser instead. Run 'owl windows' and open the page it prints; "
                    'arrow keys pressed there drive turtle1.')
            elif problem:
                self.get_logger().warning(f'No window ({problem}); running headless')
        if self.window is not None:
            self._mark_changed()

    def _open_tk_window(self) -> str | None:
        """Open the Tk window on the display; None when it opened, else why it could not."""
        try:
            import tkinter

            from turtlesim_py.window import CanvasWindow
        except ImportError as error:
            return str(error)
        try:
            self.window = CanvasWindow(on_close=self._window_closed.trigger)
        except tkinter.TclError as error:
            return str(error)
        return None

    def _on_window_closed(self) -> None:
        # Closing the window ends the process, as upstream's does.
        rclpy.try_shutdown(context=self.context)

    def _close_window(self) -> None:
        if self.window is not None:
            self.window.close()
            self.window = None

    def destroy_node(self) -> None:
        """Stop the tick thread (which closes the window), then destroy the node."""
        if self._ticks is not None:
            self._ticks.stop()  # closes the window on the tick thread
        super().destroy_node()

    def now(self) -> float:
        """The node clock's time in seconds: simulated time when use_sim_time is set."""
        return self.get_clock().now().nanoseconds * 1e-9

    # --- turtles -----------------------------------------------------------------------

    def spawn_turtle(self, name: str, x: float, y: float, theta: float) -> str:
        """Create a turtle; returns its name, or '' when it could not be created."""
        if not name:
            name = self._next_free_name()
        elif name in self.turtles:
            self.get_logger().error(f'A turtle named [{name}] already exists')
            return ''
        turtle = Turtle.spawn(name, x, y, theta, self.now(), self.get_logger(),
                              sprite=self._random.randrange(len(SHELL_COLORS)))
        try:
            self.turtles[name] = TurtleEndpoints(self, turtle)
        except Exception as error:  # rclpy rejects names that are not valid ROS names
            reason = str(error).splitlines()[0].rstrip(':')  # rclpy adds a caret diagram below
            self.get_logger().error(f'Cannot spawn a turtle named [{name}]: {reason}')
            return ''
        self._mark_changed()
        self.get_logger().info(f'Spawning turtle [{name}] at x=[{x:f}], y=[{y:f}], theta=[{theta:f}]')
        return name

    def _next_free_name(self) -> str:
        while True:
            self._spawn_counter += 1
            name = f'turtle{self._spawn_counter}'
            if name not in self.turtles:
                return name

    def _on_spawn(self, request: Spawn.Request, response: Spawn.Response) -> Spawn.Response:
        shown = non_finite(x=request.x, y=request.y, theta=request.theta)
        if shown is not None:
            self.get_logger().error(
                f'Refusing to spawn [{request.name}]: every value must be finite ({shown})')
            response.name = ''
            return response
        response.name = self.spawn_turtle(request.name, request.x, request.y, request.theta)
        return response

    def _on_kill(self, request: Kill.Request, response: Kill.Response) -> Kill.Response:
        endpoints = self.turtles.pop(request.name, None)
        if endpoints is None:
            self.get_logger().error(f'Tried to kill turtle [{request.name}], which does not exist')
        else:
            endpoints.destroy()
            self._mark_changed()
        return response

    def _on_clear(self, request: Empty.Request, response: Empty.Response) -> Empty.Response:
        self.get_logger().info('Clearing turtlesim.')
        self.canvas.clear()
        self._mark_changed()
        return response

    def _on_reset(self, request: Empty.Request, response: Empty.Response) -> Empty.Response:
        self.get_logger().info('Resetting turtlesim.')
        for endpoints in self.turtles.values():
            endpoints.destroy()
        self.turtles.clear()
        self._spawn_counter = 0
        self.spawn_turtle('', world.CENTER, world.CENTER, 0.0)
        self.canvas.clear()
        self._mark_changed()
        return response

    # --- canvas --------------------------------------------------------------------------

    def _on_parameter_event(self, event: ParameterEvent) -> None:
        if event.node == self.get_fully_qualified_name():
            self._mark_changed()

    def background(self) -> tuple[int, int, int]:
        """The background colour (r, g, b) from the background_r/g/b parameters."""
        return tuple(self.get_parameter(f'background_{c}').value for c in 'rgb')

    def render(self) -> Image.Image:
        """The canvas as it looks now: background, trails, then the turtles."""
        views = [SpriteView(name, *world.to_pixels(e.turtle.x, e.turtle.y_down), e.turtle.theta,
                            e.turtle.sprite) for name, e in self.turtles.items()]
        return self.canvas.render(self.background(), views)

    def _on_save_canvas(self, request: Trigger.Request, response: Trigger.Response) -> Trigger.Response:
        try:
            self.render().save(self.canvas_png, format='PNG')
        except OSError as error:
            response.success, response.message = False, f'cannot write {self.canvas_png}: {error}'
            self.get_logger().error(response.message)
        else:
            response.success, response.message = True, str(self.canvas_png.resolve())
        return response

    # --- the 16 ms tick ------------------------------------------------------------------

    def _tick(self) -> None:
        with self._tick_lock:
            self._step()

    def _step(self) -> None:
        if self._window_wanted:
            self._window_wanted = False
            self._open_window()
        now = self.now()
        if self.window is not None:
            self.window.pump()  # the window's events, between ticks like every ROS callback
            self._drive_with_held_keys(now)
        if self._last_tick is None:
            # The first tick only records the time (with sim time and no /clock it stays 0).
            if now != 0.0:
                self._last_tick = now
            return
        now = self._last_tick = world.tick_time(self._last_tick, now)
        debug = self.get_logger().is_enabled_for(LoggingSeverity.DEBUG)
        for endpoints in list(self.turtles.values()):
            result = endpoints.turtle.update(world.TICK_DT, now, self.canvas)
            endpoints.publish(result)
            if result.modified:
                self._mark_changed()
            if debug:
                turtle = endpoints.turtle
                self.get_logger().debug(f'[{self.get_namespace()}]: pos_x: {turtle.x:f} '
                                        f'pos_y: {turtle.y_down:f} theta: {turtle.theta:f}')
        if self._stale:
            self._publish_frame(now)

    def _drive_with_held_keys(self, now: float) -> None:
        """Arrow keys held on the window's page drive turtle1, as turtle_teleop_key's key repeat would."""
        assert self.window is not None
        drive = held_drive(self.window.held_keys())
        turtle1 = self.turtles.get('turtle1')
        if drive is not None and turtle1 is not None:
            turtle1.turtle.command_velocity(drive[0], 0.0, drive[1], now=now)

    def _mark_changed(self) -> None:
        """Something visible changed: every frame consumer needs a new frame."""
        if self.window is not None:
            self._stale.add('window')
        if self._image_pub is not None:
            self._stale.add('image')

    def _publish_frame(self, now: float) -> None:
        periods = {'window': WINDOW_PERIOD, 'image': IMAGE_PERIOD}
        due = {c for c in self._stale if now - self._last_frame[c] >= periods[c] - 0.001}
        if not due:
            return
        frame = self.render()
        self._stale -= due
        for consumer in due:
            self._last_frame[consumer] = now
        if 'window' in due and self.window is not None:  # closed since it was marked: no frame
            self.window.show(frame)
        if 'image' in due and self._image_pub is not None:
            message = CompressedImage(format='png', data=encode_png(frame))
            message.header.stamp = self.get_clock().now().to_msg()
            message.header.frame_id = 'turtlesim'
            self._image_pub.publish(message)


def parse_options(argv: list[str]) -> argparse.Namespace:
    """The node's own options (--headless, --canvas-png, --publish-image), with the ROS arguments removed."""
    parser = argparse.ArgumentParser(prog='turtlesim_node', description=__doc__.splitlines()[0])
    parser.add_argument('--headless', action='store_true', help='never open a window')
    parser.add_argument('--canvas-png', type=Path, default=Path('turtlesim.png'),
                        help='where the hidden ~/_save_canvas service writes the canvas '
                             '(default: %(default)s)')
    parser.add_argument('--publish-image', action='store_true',
                        help='publish the canvas as sensor_msgs/CompressedImage on ~/canvas/compressed')
    return parser.parse_args(remove_ros_args(argv)[1:])


def main(args: list[str] | None = None) -> None:
    """Run the simulator until Ctrl-C; args is the command line, program first (None: sys.argv)."""
    argv = sys.argv if args is None else args
    options = parse_options(argv)
    spin_node(lambda: TurtlesimNode(options.canvas_png, options.publish_image,
                                    window=not options.headless), argv)


if __name__ == '__main__':
    main()
