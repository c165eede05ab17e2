"""One turtle's state and its per-tick update, in upstream's exact order, free of ROS.

The node feeds commands in (velocity, teleports, pen, rotation goals) and calls update() once per
16 ms tick; update() draws trails on the canvas and returns what the node must publish.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Protocol

from turtlesim_py import world
from turtlesim_py.canvas import Canvas

DEFAULT_PEN_COLOR = (0xB3, 0xB8, 0xFF)
DEFAULT_PEN_WIDTH = 3
GOAL_TOLERANCE = 0.02  # rad
GOAL_SPEED = 1.0  # rad/s


class Logger(Protocol):
    """The logging a Turtle does: an rclpy logger, or a test's stand-in."""

    def info(self, message: str) -> object:
        """Log an informational line."""

    def warning(self, message: str) -> object:
        """Log a warning line."""


@dataclass(frozen=True)
class Pose:
    """What <turtle>/pose carries: world frame, y up."""

    x: float
    y: float
    theta: float
    linear_velocity: float
    angular_velocity: float


@dataclass
class Pen:
    """The turtle's pen: RGB colour, width in pixels, and whether it is down (drawing)."""

    color: tuple[int, int, int] = DEFAULT_PEN_COLOR
    width: int = DEFAULT_PEN_WIDTH
    on: bool = True


class RotationGoal:
    """A RotateAbsolute goal as the turtle sees it. The node subclasses it to reach its goal handle."""

    def __init__(self, theta: float) -> None:
        self.theta = theta
        self.start = 0.0
        self.delta = 0.0  # the result so far

    def cancel_requested(self) -> bool:
        """Whether the client asked to cancel the goal; the node's subclass answers, this base never does."""
        return False

    def publish_feedback(self, remaining: float) -> None:
        """Called on every tick while the goal is active."""

    def finish(self, status: str, delta: float) -> None:
        """Called once: status is 'succeeded', 'canceled' or 'aborted'."""


@dataclass
class TickResult:
    """What one tick gives the node: the pose and colour-sensor reading to publish, and whether to repaint."""

    pose: Pose
    color: tuple[int, int, int]
    modified: bool  # something visible changed: repaint


@dataclass
class _Teleport:
    relative: bool
    a: float  # x or linear
    b: float  # y or angular
    theta: float = 0.0


@dataclass
class Turtle:
    """One turtle: internal position (metres from the left and top), heading, velocities, pen and goal.

    Commands change it as they arrive; update() moves it one tick.
    """

    name: str
    x: float  # internal coordinates: metres from the left and from the top
    y_down: float
    theta: float
    last_command_time: float
    logger: Logger
    sprite: int = 0
    vx: float = 0.0
    vy: float = 0.0
    omega: float = 0.0
    pen: Pen = field(default_factory=Pen)
    goal: RotationGoal | None = None
    _teleports: list[_Teleport] = field(default_factory=list)

    @classmethod
    def spawn(cls, name: str, x: float, y: float, theta: float, now: float, logger: Logger,
              sprite: int = 0) -> Turtle:
        """A turtle at world (x, y, theta), unchecked: the first tick clamps and normalizes."""
        return cls(name=name, x=x, y_down=world.HEIGHT - y, theta=theta, last_command_time=now,
                   logger=logger, sprite=sprite)

    @property
    def world_y(self) -> float:
        """The turtle's y in the world frame: metres up from the bottom edge."""
        return world.HEIGHT - self.y_down

    # --- commands, applied as they arrive ---------------------------------------------------

    def command_velocity(self, linear_x: float, linear_y: float, angular_z: float, now: float) -> None:
        """A cmd_vel message. Humble applies linear.y always (there is no holonomic parameter)."""
        if self.goal is not None:
            self.logger.warning('Velocity command received during rotation goal. Aborting goal')
            self._end_goal('aborted')
        self.vx, self.vy, self.omega = linear_x, linear_y, angular_z
        self.last_command_time = now

    def teleport_absolute(self, x: float, y: float, theta: float) -> None:
        """Queue a teleport to world (x, y, theta), done at the start of the next tick."""
        self._teleports.append(_Teleport(False, x, y, theta))

    def teleport_relative(self, linear: float, angular: float) -> None:
        """Queue a move of linear m along the heading after turning by angular rad, done at the next tick."""
        self._teleports.append(_Teleport(True, linear, angular))

    def set_pen(self, r: int, g: int, b: int, width: int, off: int) -> None:
        """Off != 0 only lifts the pen; width 0 means Qt's default pen width, 1 px."""
        if off:
            self.pen.on = False
            return
        self.pen = Pen(color=(r, g, b), width=width or 1, on=True)

    def start_rotation(self, goal: RotationGoal) -> None:
        """An accepted goal replaces (aborts) the active one."""
        if self.goal is not None:
            self.logger.warning(
                'Rotation goal received before a previous goal finished. Aborting previous goal')
            self._end_goal('aborted')
        goal.start = self.theta
        goal.delta = 0.0
        self.goal = goal

    def abort_goal(self) -> None:
        """End an active goal without a log line (the turtle is going away)."""
        if self.goal is not None:
            self._end_goal('aborted')

    def _end_goal(self, status: str) -> None:
        goal, self.goal = self.goal, None
        assert goal is not None
        goal.finish(status, goal.delta)

    # --- the tick ------------------------------------------------------------------------

    def update(self, dt: float, now: float, canvas: Canvas) -> TickResult:
        """One simulation step in upstream's order; draws this tick's trail on canvas."""
        old_theta = self.theta
        modified = self._apply_teleports(canvas)
        self._process_goal(now)
        if now - self.last_command_time > world.COMMAND_TIMEOUT:
            self.vx = self.vy = self.omega = 0.0

        old_x, old_y = self.x, self.y_down
        self.x, self.y_down, self.theta = world.integrate(
            self.x, self.y_down, self.theta, self.vx, self.vy, self.omega, dt)
        if world.outside_world(self.x, self.y_down):
            self.logger.warning(
                f'Oh no! I hit the wall! (Clamping from [x={self.x:f}, y={self.y_down:f}])')
        self.x, self.y_down = world.clamp_to_world(self.x, self.y_down)

        pose = Pose(self.x, self.world_y, self.theta, math.hypot(self.vx, self.vy), self.omega)
        color = canvas.sample(world.nearest_pixel(self.x, self.y_down))

        if self.theta != old_theta:
            modified = True
        if (self.x, self.y_down) != (old_x, old_y):
            modified = True
            if self.pen.on:
                canvas.draw_line(world.to_pixels(self.x, self.y_down), world.to_pixels(old_x, old_y),
                                 self.pen.color, self.pen.width)
        return TickResult(pose, color, modified)

    def _apply_teleports(self, canvas: Canvas) -> bool:
        teleports, self._teleports = self._teleports, []
        for teleport in teleports:
            old = (self.x, self.y_down)
            if teleport.relative:
                self.theta += teleport.b
                self.x += math.cos(self.theta) * teleport.a
                self.y_down -= math.sin(self.theta) * teleport.a
            else:
                # Above the top is capped silently; below the floor is left to the wall clamp.
                self.x = teleport.a
                self.y_down = max(0.0, world.HEIGHT - teleport.b)
                self.theta = teleport.theta
            if self.pen.on:
                canvas.draw_line(world.to_pixels(*old), world.to_pixels(self.x, self.y_down),
                                 self.pen.color, self.pen.width)
        return bool(teleports)

    def _process_goal(self, now: float) -> None:
        goal = self.goal
        if goal is None:
            return
        if goal.cancel_requested():
            self.logger.info('Rotation goal canceled')
            self._end_goal('canceled')
            self.vx = self.vy = self.omega = 0.0
            return
        theta = world.float32(self.theta)
        target = world.normalize_angle(goal.theta)
        remaining = world.normalize_angle(target - theta)
        goal.delta = world.normalize_angle(goal.start - theta)
        goal.publish_feedback(remaining)
        if abs(world.normalize_angle(theta - target)) < GOAL_TOLERANCE:
            self.logger.info('Rotation goal completed successfully')
            self._end_goal('succeeded')
            self.vx = self.vy = self.omega = 0.0
            return
        self.vx = self.vy = 0.0
        self.omega = GOAL_SPEED if remaining >= 0.0 else -GOAL_SPEED
        self.last_command_time = now
