"""servo_sim: a simulated Olive servo (OLV-SRV01) with the module's topics, services and PID.

Physics runs in fixed steps of 1/physics_rate s, caught up to the wall clock before every
publication and every command, so a goal takes effect at the millisecond it arrives.
"""

from __future__ import annotations

import math
import threading
import time
from dataclasses import fields
from typing import Any

from diagnostic_msgs.msg import DiagnosticStatus, KeyValue
from olive_kit.description import GAIN_LIMITS
from owl_common.periodic import scheduled_time
from rcl_interfaces.msg import FloatingPointRange, IntegerRange, SetParametersResult
from rclpy.parameter import Parameter
from rclpy.serialization import serialize_message
from rclpy.subscription import Subscription
from sensor_msgs.msg import JointState
from std_msgs.msg import Float32
from std_srvs.srv import Trigger

from olive_sim.module_node import SENSOR_CATCH_UP, OliveModule, describe, run_module
from olive_sim.serialized import STAMP_MARKER, SerializedTemplate, markers
from olive_sim.servo_model import CONTROL_MODES, PidGains, ServoParams, ServoSim

MAX_CATCH_UP = 1.0  # s of physics run at once after a stall; beyond that the model skips time
DEFAULT_GAINS = PidGains(kp=5.0, ki=10.0, kd=0.3)

# Physical constants exposed as read-only parameters: name -> (description, unit).
PHYSICAL_PARAMETERS = {
    'inertia': 'Rotor + gearbox inertia at the output shaft [kg*m^2].',
    'stall_torque': 'Motor torque at full effort and standstill [N*m].',
    'no_load_speed': 'Speed at full effort without load, the speed limit [rad/s].',
    'max_torque': 'Current limit of the driver as a torque [N*m].',
    'viscous_friction': 'Viscous friction [N*m per rad/s].',
    'coulomb_friction': 'Coulomb (and breakaway) friction [N*m].',
    'load_mass': 'Off-axis load, e.g. the camera on the tilt servo [kg].',
    'load_offset': 'Distance of the load from the axis [m].',
    'min_position': 'Lowest position goal; goals below are clamped [rad].',
    'max_position': 'Highest position goal; goals above are clamped [rad].',
    'ambient_temperature': 'Ambient temperature of the motor [deg C].',
}


class ServoModule(OliveModule):
    """The servo_sim node: the servo model paced to the wall clock, with its topics, services and PID."""

    def __init__(self, namespace: str) -> None:
        super().__init__('servo', namespace, serial=f'srv-{namespace}')
        defaults = ServoParams()
        values = {}
        for name, description in PHYSICAL_PARAMETERS.items():
            self.declare_parameter(name, float(getattr(defaults, name)), describe(description, True))
            values[name] = self.get_parameter(name).value
        self.declare_parameter('encoder_counts', defaults.encoder_counts, describe(
            'Encoder counts per revolution.', True, integer_range=[IntegerRange(
                from_value=16, to_value=1 << 20, step=1)]))
        values['encoder_counts'] = self.get_parameter('encoder_counts').value
        self.declare_parameter('physics_rate', 1000.0, describe(
            'Physics step rate [Hz], paced to wall time.', True,
            floating_point_range=[FloatingPointRange(from_value=1000.0, to_value=20000.0)]))
        self.declare_parameter('pid_rate', 500.0, describe(
            'Rate of the firmware controller [Hz] (rounded to a divisor of physics_rate).', True,
            floating_point_range=[FloatingPointRange(from_value=10.0, to_value=20000.0)]))
        self.declare_parameter('joint_rate', 100.0, describe(
            'Publication rate of joint [Hz].', True,
            floating_point_range=[FloatingPointRange(from_value=1.0, to_value=1000.0)]))
        for name, limit in GAIN_LIMITS.items():
            self.declare_parameter(name, getattr(DEFAULT_GAINS, name), describe(
                f'PID gain {name} of the position controller (u = kp*e + ki*int(e) dt - kd*velocity, '
                'e in rad, u the motor effort -1..1).',
                floating_point_range=[FloatingPointRange(from_value=0.0, to_value=limit)]))
        self.declare_parameter('control_mode', 'position', describe(
            f"Control mode: {', '.join(CONTROL_MODES)}; each listens to its own input topic "
            '(goal/position, goal/velocity, pwm).'))
        mode = self.get_parameter('control_mode').value
        if mode not in CONTROL_MODES:
            raise ValueError(f"unknown control_mode '{mode}' (expected one of {', '.join(CONTROL_MODES)})")
        physics_rate = self.get_parameter('physics_rate').value
        self.sim = ServoSim(
            ServoParams(**{f.name: values[f.name] for f in fields(ServoParams) if f.name in values}),
            physics_rate, self.get_parameter('pid_rate').value,
            PidGains(*(self.get_parameter(n).value for n in ('kp', 'ki', 'kd'))))
        self.sim.set_mode(mode)
        self.physics_rate = physics_rate
        self._wall_start = time.monotonic()
        # The model is stepped on the joint thread and commanded from executor callbacks.
        self.lock = threading.RLock()
        self._take_over(self.handover.get('servo'))
        self.joint_template = self._joint_template(namespace)
        self.joint_traffic = self.traffic.counter()  # the joint thread's
        self.goal_traffic = self.traffic.counter()   # the executor's
        self.goal_bytes = len(serialize_message(Float32()))

        self.add_on_set_parameters_callback(self._check_parameters)
        self.add_post_set_parameters_callback(self._apply_parameters)
        self.joint_publisher = self.create_publisher(JointState, self.topic('joint'), 10)
        self.diagnostics_publisher = self.create_publisher(
            DiagnosticStatus, self.topic('joint/diagnostics'), 10)
        self.goal_subscription: Subscription | None = None
        self._subscribe_for_mode(mode)
        self.create_service(Trigger, self.topic('setTorqueEnable'), self._on_torque_enable)
        self.create_service(Trigger, self.topic('setTorqueDisable'), self._on_torque_disable)
        self.joint_thread = self.create_periodic(self.get_parameter('joint_rate').value,
                                                 self._publish_joint, 'joint', catch_up=SENSOR_CATCH_UP)
        self.diagnostics_timer = self.create_timer(1.0, self._publish_diagnostics)

    def _take_over(self, state: Any) -> None:
        """Put the shaft where the process before a restart left it.

        After Restart Services the torque and goal are taken over too (restart.py); a reboot hands
        over the shaft only.
        """
        if not isinstance(state, dict):
            return
        try:
            position = float(state['position'])
            goal = self.sim.clamp_goal(float(state.get('goal', position)))
        except (KeyError, TypeError, ValueError):
            return
        if not (math.isfinite(position) and math.isfinite(goal)):
            return
        self.sim.state.position = position
        self.sim.state.temperature = float(state.get('temperature', self.sim.state.temperature))
        if state.get('torque') is True:
            self.sim.enable_torque(True)
            self.sim.goal_position = goal

    def handover_state(self) -> dict[str, Any]:
        """What the next process keeps: the base state and the shaft's position and temperature.

        After Restart Services (no restart delay) the motor driver's torque and goal too.
        """
        with self.lock:
            self._advance_to_now()
            servo = {'position': self.sim.state.position, 'temperature': self.sim.state.temperature}
            if not self.restart_delay:  # Restart Services: the motor driver keeps its state
                servo.update(torque=self.sim.torque_enabled, goal=self.sim.goal_position)
        return {**super().handover_state(), 'servo': servo}

    @staticmethod
    def _joint_template(namespace: str) -> SerializedTemplate:
        """The serialized joint message to fill with position, velocity and effort."""
        values = markers(3)
        msg = JointState(name=[f'{namespace}_joint'], position=values[:1], velocity=values[1:2],
                         effort=values[2:])
        msg.header.stamp.sec, msg.header.stamp.nanosec = STAMP_MARKER
        msg.header.frame_id = f'{namespace}_rotor_link'
        return SerializedTemplate(serialize_message(msg), values)

    # -- physics pacing ---------------------------------------------------------------------

    def _advance_to_now(self) -> None:
        """Run the fixed-step model until its time reaches the wall clock (hold self.lock)."""
        self._advance_to(time.monotonic())

    def _advance_to(self, instant: float) -> None:
        """Run the fixed-step model until its time reaches instant, a time.monotonic() (hold self.lock).

        A model already past instant (a goal or a service advanced it) stays where it is.
        """
        elapsed = instant - self._wall_start
        behind = elapsed - self.sim.time
        if behind > MAX_CATCH_UP:
            self.warn('stall', f'physics fell {behind:.2f} s behind wall time (process stalled): '
                      'skipping ahead')
            self._wall_start += behind - MAX_CATCH_UP
            elapsed = instant - self._wall_start
        self.sim.advance(max(0, int(elapsed * self.physics_rate) - self.sim.steps))

    # -- parameters -------------------------------------------------------------------------

    def _check_parameters(self, parameters: list[Parameter]) -> SetParametersResult:
        for p in parameters:
            if p.name == 'control_mode' and p.value not in CONTROL_MODES:
                return SetParametersResult(successful=False, reason=(
                    f"unknown control_mode '{p.value}': expected one of {', '.join(CONTROL_MODES)}"))
            if p.name in GAIN_LIMITS and not math.isfinite(p.value):
                return SetParametersResult(successful=False, reason=f'{p.name} must be finite')
        return SetParametersResult(successful=True)

    def _apply_parameters(self, parameters: list[Parameter]) -> None:
        for p in parameters:
            with self.lock:
                self._advance_to_now()
                if p.name in GAIN_LIMITS:
                    setattr(self.sim.pid.gains, p.name, p.value)
                elif p.name == 'control_mode' and p.value != self.sim.mode:
                    self.sim.set_mode(p.value)
            if p.name == 'control_mode':
                self._subscribe_for_mode(p.value)

    def _subscribe_for_mode(self, mode: str) -> None:
        # Only the active mode's input exists, so `ros2 topic list` shows what the course shows
        # for a servo in position mode (goal/position, no goal/velocity or pwm).
        if self.goal_subscription is not None:
            self.destroy_subscription(self.goal_subscription)
        topic, callback = {
            'position': ('goal/position', self._on_goal_position),
            'velocity': ('goal/velocity', self._on_goal_velocity),
            'pwm': ('pwm', self._on_pwm),
        }[mode]
        self.goal_subscription = self.create_subscription(Float32, self.topic(topic), callback, 10)

    # -- commands ---------------------------------------------------------------------------

    def _accept(self, topic: str, value: float) -> bool:
        """Whether a command may act: finite, and torque on (both warned about otherwise)."""
        if not math.isfinite(value):
            self.warn(f'{topic} {value}', f'{self.topic(topic)}: ignored {value}, a goal must be a '
                      'finite number')
            return False
        if not self.sim.torque_enabled:
            self.warn(f'{topic} torque off', f'{self.topic(topic)}: ignored, torque is disabled (call '
                      f"{self.topic('setTorqueEnable')} first)")
            return False
        return True

    def _on_goal_position(self, msg: Float32) -> None:
        self.goal_traffic.received += self.goal_bytes
        if not self._accept('goal/position', msg.data):
            return
        goal = self.sim.clamp_goal(msg.data)
        if goal != msg.data:
            p = self.sim.params
            self.warn('position clamped', f'goal/position {msg.data:.4f} rad is outside '
                      f'[{p.min_position:.4f}, {p.max_position:.4f}]: clamped to {goal:.4f}')
        with self.lock:
            self._advance_to_now()
            self.sim.goal_position = goal

    def _on_goal_velocity(self, msg: Float32) -> None:
        self.goal_traffic.received += self.goal_bytes
        if not self._accept('goal/velocity', msg.data):
            return
        limit = self.sim.params.no_load_speed
        goal = max(-limit, min(limit, msg.data))
        if goal != msg.data:
            self.warn('velocity clamped', f'goal/velocity {msg.data:.3f} rad/s is beyond the speed '
                      f'limit {limit:.3f}: clamped')
        with self.lock:
            self._advance_to_now()
            self.sim.goal_velocity = goal

    def _on_pwm(self, msg: Float32) -> None:
        self.goal_traffic.received += self.goal_bytes
        if not self._accept('pwm', msg.data):
            return
        if not -1.0 <= msg.data <= 1.0:
            self.warn('pwm range', f'pwm {msg.data} ignored: the duty cycle must be within -1..1')
            return
        with self.lock:
            self._advance_to_now()
            self.sim.pwm = msg.data

    def _on_torque_enable(self, request: Trigger.Request, response: Trigger.Response) -> Trigger.Response:
        with self.lock:
            self._advance_to_now()
            already = self.sim.torque_enabled
            self.sim.enable_torque(True)
        response.success = True
        response.message = 'torque already enabled' if already else 'torque enabled'
        self.get_logger().info(response.message)
        return response

    def _on_torque_disable(self, request: Trigger.Request, response: Trigger.Response) -> Trigger.Response:
        with self.lock:
            self._advance_to_now()
            already = not self.sim.torque_enabled
            self.sim.enable_torque(False)
        response.success = True
        response.message = 'torque already disabled' if already else 'torque disabled'
        self.get_logger().info(response.message)
        return response

    # -- outputs ----------------------------------------------------------------------------

    def _publish_joint(self) -> None:
        # Measured at its due time on the joint_rate schedule and stamped with the model's time, so
        # a loaded machine delays the messages but keeps their spacing (as the IMU does).
        with self.lock:
            self._advance_to(scheduled_time())
            values = (self.sim.measured_position(), self.sim.state.velocity, self.sim.state.torque)
            measured_at = self._wall_start + self.sim.time
        joint = self.joint_template.fill(self.ros_time_at(measured_at), values)
        self.joint_publisher.publish(joint)
        self.joint_traffic.sent += len(joint)

    def _publish_diagnostics(self) -> None:
        with self.lock:
            values = self._diagnostic_values()
        level, message = self.status_level()
        self.diagnostics_publisher.publish(DiagnosticStatus(
            level=level, name=self.topic('joint').rstrip('/'), message=message,
            hardware_id=self.serial, values=[KeyValue(key=k, value=v) for k, v in values.items()]))

    def _diagnostic_values(self) -> dict[str, str]:
        s = self.sim
        return {
            'torque_enabled': str(s.torque_enabled).lower(),
            'control_mode': s.mode,
            'goal_position': f'{s.goal_position:.4f}',
            'goal_velocity': f'{s.goal_velocity:.4f}',
            'pwm': f'{s.pwm:.3f}',
            'position': f'{s.measured_position():.4f}',
            'velocity': f'{s.state.velocity:.4f}',
            'effort': f'{s.state.torque:.4f}',
            'motor_effort': f'{s.effort:.3f}',
            'temperature': f'{s.state.temperature:.2f}',
        }

    def temperature(self) -> float:
        """The motor's temperature in deg C, from the model (it heats with the torque)."""
        return self.sim.state.temperature

    def status_level(self) -> tuple[bytes, str]:
        """WARN 'motor hot' above 70 deg C, else OK saying whether the torque is enabled."""
        if self.sim.state.temperature > 70.0:
            return DiagnosticStatus.WARN, 'motor hot'
        return DiagnosticStatus.OK, 'torque enabled' if self.sim.torque_enabled else 'torque disabled'

    def status_values(self) -> dict[str, str]:
        """The status message's torque_enabled and control_mode entries."""
        return {'torque_enabled': str(self.sim.torque_enabled).lower(), 'control_mode': self.sim.mode}


def main(args: list[str] | None = None) -> None:
    """servo_sim's entry point: one servo module, in namespace `pan` by default."""
    run_module(ServoModule, 'pan', args)


if __name__ == '__main__':
    main()
