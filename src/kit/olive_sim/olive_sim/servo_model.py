"""The servo as a pure, fixed-step model: DC motor + gearbox, friction, gravity load, firmware PID.

No ROS and no wall clock here: the node calls ServoSim.step() once per physics period and the
tests call it in a loop, so every number (rise time, overshoot, remaining error) is reproducible.

Units: angles in rad, speeds in rad/s, torques in N*m at the output shaft. The controller output
is a normalised motor effort u in [-1, 1] (the same scale as the `pwm` topic): u = 1 means the
full supply voltage across the motor. The PID gains act on the error in rad, in continuous time:
u = kp*e + ki*integral(e dt) - kd*d(position)/dt (derivative on the measured position, so a new
goal gives no derivative kick; between goal changes it equals kd*de/dt).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

GRAVITY = 9.81  # m/s^2

CONTROL_MODES = ('position', 'velocity', 'pwm')


@dataclass(frozen=True)
class ServoParams:
    """Physical constants of one servo and its load (defaults: an OLV-SRV01-sized servo)."""

    inertia: float = 0.02             # kg*m^2, rotor + gearbox reflected to the output + horn
    stall_torque: float = 1.5         # N*m at u = 1 and standstill
    no_load_speed: float = 6.0        # rad/s at u = 1 without load (the speed limit)
    max_torque: float = 1.5           # N*m, the driver's current limit (torque limit)
    viscous_friction: float = 0.01    # N*m per rad/s
    coulomb_friction: float = 0.15    # N*m, also the breakaway (static) friction
    load_mass: float = 0.0            # kg carried off-axis (the camera on the tilt servo)
    load_offset: float = 0.04         # m from the axis to the load's centre of mass
    min_position: float = -math.pi    # rad, goals outside are clamped
    max_position: float = math.pi
    encoder_counts: int = 4096        # per revolution; the controller sees quantised angles
    ambient_temperature: float = 25.0  # deg C
    stall_power: float = 6.0          # W of heat in the motor at stall torque
    thermal_resistance: float = 8.0   # K/W, motor to ambient
    thermal_time_constant: float = 60.0  # s

    def problems(self) -> list[str]:
        """Why these constants cannot make a physical servo (empty when they can)."""
        found = []
        for name in ('inertia', 'stall_torque', 'no_load_speed', 'max_torque', 'load_offset',
                     'thermal_resistance', 'thermal_time_constant'):
            value = getattr(self, name)
            if not (math.isfinite(value) and value > 0):
                found.append(f'{name} must be a positive finite number, got {value}')
        for name in ('viscous_friction', 'coulomb_friction', 'load_mass', 'stall_power'):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0):
                found.append(f'{name} must be zero or positive, got {value}')
        if not (self.min_position < self.max_position):
            found.append(f'min_position ({self.min_position}) must be below max_position '
                         f'({self.max_position})')
        if self.encoder_counts < 16:
            found.append(f'encoder_counts must be at least 16, got {self.encoder_counts}')
        return found


@dataclass
class PidGains:
    """The position PID's gains, for an error in rad and u in [-1, 1]: kp 1/rad, ki 1/(rad*s), kd s/rad."""

    kp: float = 1.0
    ki: float = 0.0
    kd: float = 0.0


@dataclass
class Pid:
    """The firmware's position PID with conditional integration as anti-windup."""

    gains: PidGains = field(default_factory=PidGains)
    integral_zone: float = 0.1  # rad: the error is integrated only closer to the goal than this
    integral: float = 0.0       # the integral term's contribution to the output

    def update(self, error: float, measured_velocity: float, dt: float) -> float:
        """The output u in [-1, 1] for the error (rad) and measured velocity (rad/s), dt s after the last."""
        g = self.gains
        proportional_and_derivative = g.kp * error - g.kd * measured_velocity
        unsaturated = proportional_and_derivative + self.integral
        # The integral keeps ki*sum(e*dt), so a new ki acts from now on without a jump. It grows
        # only near the goal and while the output is not pinned at its limit in the error's
        # direction: otherwise it winds up during a long move and throws the servo past the goal.
        if abs(error) < self.integral_zone and (abs(unsaturated) < 1.0 or unsaturated * error < 0):
            self.integral = clamp(self.integral + g.ki * error * dt, -1.0, 1.0)
        return clamp(proportional_and_derivative + self.integral, -1.0, 1.0)

    def reset(self) -> None:
        """Clear the integral term, for a fresh start (a mode change, torque switched on)."""
        self.integral = 0.0


def clamp(value: float, low: float, high: float) -> float:
    """Value limited to the range low..high."""
    return low if value < low else high if value > high else value


@dataclass
class ServoState:
    """The servo's physical state at the output shaft, which ServoSim advances."""

    position: float = 0.0      # rad
    velocity: float = 0.0      # rad/s
    torque: float = 0.0        # N*m from the motor, the `effort` of the joint state
    temperature: float = 25.0  # deg C of the motor


class ServoSim:
    """One servo: physics at physics_rate, controller at pid_rate, the module's command inputs."""

    def __init__(self, params: ServoParams | None = None, physics_rate: float = 1000.0,
                 pid_rate: float = 500.0, gains: PidGains | None = None) -> None:
        self.params = params or ServoParams()
        problems = self.params.problems()
        if problems:
            raise ValueError('; '.join(problems))
        if not physics_rate >= 1000.0:
            raise ValueError(f'physics_rate must be at least 1000 Hz, got {physics_rate}')
        if not 0 < pid_rate <= physics_rate:
            raise ValueError(f'pid_rate must be in (0, physics_rate={physics_rate}], got {pid_rate}')
        self.dt = 1.0 / physics_rate
        # The controller runs every pid_every physics steps (its rate rounds to a whole divisor).
        self.pid_every = max(1, round(physics_rate / pid_rate))
        self.pid = Pid(gains or PidGains())
        self.state = ServoState(temperature=self.params.ambient_temperature)
        self.time = 0.0
        self.steps = 0
        self.mode = 'position'
        self.torque_enabled = False
        self.goal_position = 0.0
        self.goal_velocity = 0.0
        self.velocity_ki = 2.0  # 1/rad, integral gain of the velocity loop
        self.pwm = 0.0
        self.effort = 0.0  # controller output u held between controller ticks
        self._velocity_integral = 0.0
        self._last_measured = self.measured_position()

    # -- commands (the node validates; these only store) ------------------------------------

    def set_mode(self, mode: str) -> None:
        """Switch to one of CONTROL_MODES (the controller starts afresh); ValueError for any other."""
        if mode not in CONTROL_MODES:
            raise ValueError(f"unknown control mode '{mode}' (expected one of {', '.join(CONTROL_MODES)})")
        if mode != self.mode:
            self.mode = mode
            self._reset_controller()

    def enable_torque(self, enabled: bool) -> None:
        """Switch the motor driver on or off; switched on, the servo holds the joint where it is."""
        if enabled and not self.torque_enabled:
            # Hold where the joint is, as a servo does when its torque comes on.
            self.goal_position = self.clamp_goal(self.state.position)
            self.goal_velocity = 0.0
            self.pwm = 0.0
            self._reset_controller()
        self.torque_enabled = enabled

    def clamp_goal(self, position: float) -> float:
        """A position goal limited to the servo's range, min_position..max_position."""
        return clamp(position, self.params.min_position, self.params.max_position)

    def _reset_controller(self) -> None:
        self.pid.reset()
        self._velocity_integral = 0.0
        self.effort = 0.0

    # -- simulation ------------------------------------------------------------------------

    def measured_position(self) -> float:
        """The encoder's reading of the output angle."""
        count = 2 * math.pi / self.params.encoder_counts
        return round(self.state.position / count) * count

    def _control(self) -> float:
        measured = self.measured_position()
        control_dt = self.pid_every * self.dt
        measured_velocity = (measured - self._last_measured) / control_dt
        self._last_measured = measured
        if self.mode == 'position':
            return self.pid.update(self.goal_position - measured, measured_velocity, control_dt)
        if self.mode == 'velocity':
            # Feed-forward of the no-load speed plus an integral on the speed error.
            error = self.goal_velocity - measured_velocity
            self._velocity_integral = clamp(self._velocity_integral + error * control_dt, -1.0, 1.0)
            return clamp(self.goal_velocity / self.params.no_load_speed
                         + self.velocity_ki * self._velocity_integral, -1.0, 1.0)
        return clamp(self.pwm, -1.0, 1.0)

    def step(self) -> None:
        """Advance the model by one physics period."""
        self.advance(1)

    def advance(self, count: int) -> None:
        """Advance the model by `count` physics periods, exactly as `count` single steps would.

        The node runs about ten steps per joint publication; the constants are looked up once per
        batch rather than once per step, which halves the time of a step.
        """
        p, s = self.params, self.state
        dt, pid_every, torque_enabled = self.dt, self.pid_every, self.torque_enabled
        stall_torque, no_load_speed, max_torque = p.stall_torque, p.no_load_speed, p.max_torque
        coulomb, viscous, inertia = p.coulomb_friction, p.viscous_friction, p.inertia
        # The off-axis load's torque is gravity * cos(position): largest with the arm level (tilt
        # 0), pulling it down (+).
        gravity = p.load_mass * GRAVITY * p.load_offset
        stall_power, ambient = p.stall_power, p.ambient_temperature
        resistance, time_constant = p.thermal_resistance, p.thermal_time_constant
        steps = self.steps
        for _ in range(count):
            if steps % pid_every == 0:
                self.effort = self._control() if torque_enabled else 0.0
            velocity = s.velocity
            if torque_enabled:
                torque = clamp(stall_torque * (self.effort - velocity / no_load_speed),
                               -max_torque, max_torque)
            else:
                torque = 0.0  # driver off: the joint coasts
            s.torque = torque
            drive = torque + gravity * math.cos(s.position)
            # At standstill static friction holds the joint unless the drive overcomes it.
            if velocity != 0.0 or abs(drive) > coulomb:
                friction = math.copysign(coulomb, velocity if velocity != 0.0 else drive)
                acceleration = (drive - viscous * velocity - friction) / inertia
                new_velocity = velocity + acceleration * dt
                if velocity != 0.0 and new_velocity * velocity < 0:
                    new_velocity = 0.0  # friction stops the joint; it cannot push it backwards
                s.velocity = new_velocity
                s.position += new_velocity * dt
            # The motor heats with effort squared toward its equilibrium temperature.
            equilibrium = ambient + resistance * (stall_power * (torque / stall_torque) ** 2)
            s.temperature += (equilibrium - s.temperature) * dt / time_constant
            steps += 1
        self.steps = steps
        self.time = steps * dt


@dataclass(frozen=True)
class StepMetrics:
    """The step-response numbers the course's PID exercise observes, for one move."""

    rise_time: float              # s from 10 % to 90 % of the step (inf if never reached)
    overshoot: float              # rad beyond the goal, 0 if none
    steady_state_error: float     # rad, |goal - mean position| over the last 0.2 s
    settling_time: float          # s until the error stays within 2 % of the step (inf if never)


def step_metrics(times: list[float], positions: list[float], start: float, goal: float,
                 tail: float = 0.2) -> StepMetrics:
    """Classic step-response numbers for a move from start to goal sampled at times (s from the step)."""
    if len(times) != len(positions) or len(times) < 2:
        raise ValueError('need at least two samples, as many times as positions')
    span = goal - start
    if span == 0:
        raise ValueError('start and goal are equal: no step to measure')
    progress = [(x - start) / span for x in positions]  # 0 at start, 1 at goal
    t10 = next((t for t, f in zip(times, progress, strict=True) if f >= 0.1), math.inf)
    t90 = next((t for t, f in zip(times, progress, strict=True) if f >= 0.9), math.inf)
    overshoot = max(0.0, (max(progress) - 1.0) * abs(span))
    tail_start = times[-1] - tail
    tail_positions = [x for t, x in zip(times, positions, strict=True) if t >= tail_start]
    error = abs(goal - sum(tail_positions) / len(tail_positions))
    band = 0.02 * abs(span)
    settling = 0.0
    for t, x in zip(times, positions, strict=True):
        if abs(goal - x) > band:
            settling = t
    if abs(goal - positions[-1]) > band:
        settling = math.inf
    return StepMetrics(t90 - t10, overshoot, error, settling)


def simulate_step(gains: PidGains, goal: float = 1.57, duration: float = 3.0,
                  params: ServoParams | None = None, physics_rate: float = 1000.0,
                  pid_rate: float = 500.0, sample_rate: float = 100.0) -> StepMetrics:
    """The step-response numbers of the course's PID exercise (section 4.4, the appendix 5.3 script).

    Torque on at 0 rad, then a goal step to `goal`, watched for `duration` s (the script flips the goal
    every 3 s).
    """
    sim = ServoSim(params, physics_rate, pid_rate, gains)
    sim.enable_torque(True)
    start = sim.state.position
    sim.goal_position = sim.clamp_goal(goal)
    every = max(1, round(physics_rate / sample_rate))
    times, positions = [], []
    for _ in range(round(duration * physics_rate)):
        sim.step()
        if sim.steps % every == 0:
            times.append(sim.time)
            positions.append(sim.state.position)
    return step_metrics(times, positions, start, sim.goal_position)


# The course's section 4.4 sequence: Kp = 1 alone; Kp raised "until the servo reaches the desired
# speed"; Ki introduced from 0.01 and raised until no error remains; Kd = 1.0 against the overshoot.
COURSE_GAIN_SEQUENCE = (
    ('Kp=1', PidGains(1.0, 0.0, 0.0)),
    ('Kp=5', PidGains(5.0, 0.0, 0.0)),
    ('Kp=5 Ki=10', PidGains(5.0, 10.0, 0.0)),
    ('Kp=5 Ki=10 Kd=1', PidGains(5.0, 10.0, 1.0)),
)


def course_exercise(sequence: tuple[tuple[str, PidGains], ...] = COURSE_GAIN_SEQUENCE,
                    goals: tuple[float, float] = (1.57, 0.0), period: float = 3.0,
                    params: ServoParams | None = None, sample_rate: float = 100.0
                    ) -> list[tuple[str, StepMetrics]]:
    """The step-response numbers of every goal flip of one servo running the appendix 5.3 script.

    The goal flips every `period` s; the gains are changed before each flip as the exercise goes.
    """
    sim = ServoSim(params)
    sim.enable_torque(True)
    every = max(1, round(1.0 / (sample_rate * sim.dt)))
    results = []
    for index, (label, gains) in enumerate(sequence):
        sim.pid.gains = PidGains(gains.kp, gains.ki, gains.kd)
        start, t0 = sim.state.position, sim.time
        sim.goal_position = sim.clamp_goal(goals[index % 2])
        times, positions = [], []
        for _ in range(round(period / sim.dt)):
            sim.step()
            if sim.steps % every == 0:
                times.append(sim.time - t0)
                positions.append(sim.state.position)
        results.append((label, step_metrics(times, positions, start, sim.goal_position)))
    return results
