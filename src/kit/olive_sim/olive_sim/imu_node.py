"""imu_sim: a simulated Olive IMU (OLV-IMU01) with the module's topics and services."""

from __future__ import annotations

from typing import Any

from geometry_msgs.msg import Quaternion as QuaternionMsg
from olive_kit.description import IMU_NAMESPACE
from owl_common.quaternion import Quaternion
from rcl_interfaces.msg import FloatingPointRange
from std_srvs.srv import Trigger

from olive_sim.imu_model import MOTION_SOURCES, CommandedMotion, Motion, RecordedMotion, ScriptedMotion
from olive_sim.imu_output import ImuOutput
from olive_sim.module_node import OliveModule, describe, run_module


class ImuModule(OliveModule):
    """The imu_sim node: readings of a scripted, commanded or recorded motion, and the IMU's services."""

    def __init__(self, namespace: str) -> None:
        super().__init__('imu', namespace, serial=namespace.lstrip('x'))
        self.declare_parameter('motion', 'scripted', describe(
            "Where the true motion comes from: 'scripted' (hand-held tilting and turning), 'command' "
            '(the true_orientation topic of this node) or \'file\' (motion_file).', True))
        self.declare_parameter('motion_file', '', describe(
            'CSV of t,roll,pitch,yaw or t,qx,qy,qz,qw rows, looped (motion:=file).', True))
        self.declare_parameter('command_max_rate', 3.0, describe(
            'Fastest turn toward a commanded orientation [rad/s] (motion:=command).', True,
            floating_point_range=[FloatingPointRange(from_value=0.01, to_value=100.0)]))
        source = self.get_parameter('motion').value
        if source not in MOTION_SOURCES:
            raise ValueError(f"unknown motion '{source}' (expected one of {', '.join(MOTION_SOURCES)})")
        self.motion: Motion
        if source == 'scripted':
            self.motion = ScriptedMotion()
        elif source == 'file':
            self.motion = RecordedMotion(self.get_parameter('motion_file').value)
        else:
            commanded = CommandedMotion(self.get_parameter('command_max_rate').value)
            held = self.handover.get('held')  # the hand still holds the IMU after a restart
            if isinstance(held, list) and len(held) == 4:
                commanded.hold((held[0], held[1], held[2], held[3]))
            self.motion = commanded
            # A simulator control, so it lives under the node's name, not in the module's topics.
            self.create_subscription(QuaternionMsg, '~/true_orientation', self._on_command, 10)
        self.output = ImuOutput(self, self.topic, f'{namespace}_base_link', self.motion.orientation)
        for name, handler in (('setBias', self._on_set_bias),
                              ('setZeroQuaternion', self._on_set_zero_quaternion),
                              ('setZeroPose', self._on_set_zero_pose)):
            self.create_service(Trigger, self.topic(name), handler)

    def _on_command(self, msg: QuaternionMsg) -> None:
        q: Quaternion = (msg.x, msg.y, msg.z, msg.w)
        try:
            with self.output.lock:
                if isinstance(self.motion, CommandedMotion):  # always: only motion:=command subscribes
                    self.motion.command(q)
        except ValueError as error:
            self.get_logger().warning(f'true_orientation ignored: {error}')

    def _answer(self, response: Trigger.Response, result: tuple[bool, str]) -> Trigger.Response:
        response.success, response.message = result
        log = self.get_logger().info if response.success else self.get_logger().warning
        log(response.message)
        return response

    def _on_set_bias(self, request: Trigger.Request, response: Trigger.Response) -> Trigger.Response:
        with self.output.lock:
            result = self.output.sensor.set_bias()
        return self._answer(response, result)

    def _on_set_zero_quaternion(self, request: Trigger.Request,
                                response: Trigger.Response) -> Trigger.Response:
        with self.output.lock:
            result = self.output.sensor.set_zero_orientation()
        return self._answer(response, result)

    def _on_set_zero_pose(self, request: Trigger.Request, response: Trigger.Response) -> Trigger.Response:
        # The pose of a still-standing IMU is its orientation: position is not integrated here.
        with self.output.lock:
            ok, _ = self.output.sensor.set_zero_orientation()
        return self._answer(response, (ok, 'pose zeroed: orientation is now the identity'))

    def temperature(self) -> float:
        """The IMU board's temperature in deg C, a constant 31.5."""
        return 31.5

    def imu_orientation(self) -> Quaternion | None:
        """The orientation last published on the imu topic (None before the first reading)."""
        return self.output.latest

    def handover_state(self) -> dict[str, Any]:
        """The base state, the motion's time and a commanded target: a restart goes on where it was."""
        state = {**super().handover_state(), 'imu_time': self.output.motion_time()}
        if isinstance(self.motion, CommandedMotion):
            state['held'] = list(self.motion.target)
        return state


def main(args: list[str] | None = None) -> None:
    """imu_sim's entry point: one IMU module, by default in the namespace of the course's IMU."""
    run_module(ImuModule, IMU_NAMESPACE, args)


if __name__ == '__main__':
    main()
