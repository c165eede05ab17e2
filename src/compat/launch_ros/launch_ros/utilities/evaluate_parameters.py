"""Normalised node parameters evaluated in a launch context: typed values, and parameter file paths."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any

from launch.substitution import Substitution
from launch.utilities import perform_substitutions

from launch_ros.parameter_descriptions import Parameter, ParameterFile, ParameterValue, yaml_value
from launch_ros.parameters_type import EvaluatedParameters, EvaluatedParameterValue, Parameters

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext

__all__ = ['evaluate_parameter_dict', 'evaluate_parameters']

_NOT_NORMALIZED = 'pass the parameters through launch_ros.utilities.normalize_parameters() first'


def _as_tuple(value: Any) -> Any:
    """Lists read from YAML become tuples, the container upstream gives for sequences."""
    return tuple(value) if isinstance(value, list) else value


def _evaluate_value(context: LaunchContext, name: str, value: Any) -> EvaluatedParameterValue:
    if isinstance(value, ParameterValue):
        return value.evaluate(context)
    if isinstance(value, (str, bool, int, float, bytes)):
        return value
    if not isinstance(value, tuple) or not value:
        raise TypeError(f"parameter '{name}': unexpected normalized value {value!r}; {_NOT_NORMALIZED}")
    if isinstance(value[0], Substitution):
        # One string made of substitutions, read as YAML.
        return _as_tuple(yaml_value(perform_substitutions(context, list(value)), name))
    if isinstance(value[0], Sequence) and not isinstance(value[0], (str, bytes)):
        # A list of strings, each made of substitutions and read as YAML; one type for all.
        items = [yaml_value(perform_substitutions(context, list(item)), name) for item in value]
        kinds = {type(item) for item in items}
        if len(kinds) != 1 or not kinds <= {bool, int, float, str}:
            raise TypeError(f"parameter '{name}': expected a list of one type (bool, int, float or str), "
                            f'got {items!r}')
        return tuple(items)
    return tuple(value)  # numbers or bools, already of one type


def evaluate_parameter_dict(context: LaunchContext, parameters: Mapping[Any, Any]
                            ) -> dict[str, EvaluatedParameterValue]:
    """A normalised {name substitutions: value} dict as {name: typed value}; sequences become tuples."""
    if not isinstance(parameters, Mapping):
        raise TypeError(f"parameters must be a dict, got '{type(parameters).__name__}'")
    evaluated: dict[str, EvaluatedParameterValue] = {}
    for key, value in parameters.items():
        if not isinstance(key, tuple):
            raise TypeError(f'parameter name {key!r} is not a tuple of substitutions; {_NOT_NORMALIZED}')
        name = perform_substitutions(context, list(key))
        evaluated[name] = _evaluate_value(context, name, value)
    return evaluated


def evaluate_parameters(context: LaunchContext, parameters: Parameters) -> EvaluatedParameters:
    """Normalised parameters evaluated, as a tuple in the same order.

    A ParameterFile gives its path (pathlib.Path), a dict gives {name: value}, a Parameter is passed
    on as it is (its user evaluates it). TypeError for anything else.
    """
    evaluated: list[Any] = []
    for item in parameters:
        if isinstance(item, ParameterFile):
            evaluated.append(item.evaluate(context))
        elif isinstance(item, Parameter):
            evaluated.append(item)
        elif isinstance(item, Mapping):
            evaluated.append(evaluate_parameter_dict(context, item))
        else:
            raise TypeError(f"unexpected item {item!r} ('{type(item).__name__}') in parameters; "
                            f'{_NOT_NORMALIZED}')
    return tuple(evaluated)
