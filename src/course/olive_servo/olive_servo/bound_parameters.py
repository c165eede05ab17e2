"""The servos' goal bounds as parameters of a node: pan_min, pan_max, tilt_min, tilt_max."""

from collections.abc import Sequence

from rcl_interfaces.msg import FloatingPointRange, ParameterDescriptor, SetParametersResult
from rclpy.node import Node
from rclpy.parameter import Parameter

from olive_servo.goals import BOUND_LIMIT, KIT_BOUNDS, bounds_problem


class BoundParameters:
    """Declares `<servo>_min` and `<servo>_max` for each servo, with the kit's bounds as defaults.

    Each bound lies within +-BOUND_LIMIT (the descriptor refuses other values and types); a min
    not below its max raises ValueError at start and is refused with the reason at runtime.
    """

    def __init__(self, node: Node, servos: Sequence[str]) -> None:
        self.node = node
        self.servos = tuple(servos)
        for servo in self.servos:
            low, high = KIT_BOUNDS[servo]
            node.declare_parameter(f'{servo}_min', low, self._descriptor(f'Smallest {servo} goal, rad.'))
            node.declare_parameter(f'{servo}_max', high, self._descriptor(f'Largest {servo} goal, rad.'))
            problem = bounds_problem(servo, *self.bounds(servo))
            if problem:
                raise ValueError(problem)
        node.add_on_set_parameters_callback(self.check)

    @staticmethod
    def _descriptor(description: str) -> ParameterDescriptor:
        return ParameterDescriptor(
            description=description,
            floating_point_range=[FloatingPointRange(from_value=-BOUND_LIMIT, to_value=BOUND_LIMIT)])

    def bounds(self, servo: str, new: dict[str, float] | None = None) -> tuple[float, float]:
        """(min, max) of a servo's goals; values in new take precedence over the current ones."""
        new = new or {}
        low, high = f'{servo}_min', f'{servo}_max'
        return (new.get(low, self.node.get_parameter(low).value),
                new.get(high, self.node.get_parameter(high).value))

    def all(self) -> dict[str, tuple[float, float]]:
        """Every servo's (min, max)."""
        return {servo: self.bounds(servo) for servo in self.servos}

    def check(self, parameters: list[Parameter]) -> SetParametersResult:
        # The descriptors already refuse other types and values beyond +-pi; this guards each pair.
        new = {p.name: p.value for p in parameters}
        problems = [bounds_problem(servo, *self.bounds(servo, new)) for servo in self.servos]
        reason = '; '.join(p for p in problems if p)
        return SetParametersResult(successful=not reason, reason=reason)
