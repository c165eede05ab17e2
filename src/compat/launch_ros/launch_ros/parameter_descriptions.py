"""Descriptions of node parameters: a value with a forced type, a parameter file, one parameter."""

from __future__ import annotations

import pathlib
import tempfile
from typing import TYPE_CHECKING, Any

import yaml
from launch.substitution import (
    SomeSubstitutionsType,
    Substitution,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext

__all__ = ['Parameter', 'ParameterFile', 'ParameterValue']


class ParameterValue:
    """A parameter value whose type is forced (e.g. value_type=str keeps a URDF text a string)."""

    def __init__(self, value: Any, *, value_type: Any = None) -> None:
        self.value = value
        self.value_type = value_type

    def evaluate(self, context: LaunchContext) -> Any:
        """The value for the node, forced to value_type when one is given.

        Text under value_type=str stays the performed text as it is; other values are evaluated as in a
        parameters dict, then coerced (TypeError if they cannot be).
        """
        from launch_ros.parameters import coerce_value, evaluate_value

        if self.value_type is str and _is_text(self.value):
            return perform_substitutions(context, normalize_to_list_of_substitutions(self.value))
        value = evaluate_value(context, self.value)
        return value if self.value_type is None else coerce_value(value, self.value_type)


def _is_text(value: Any) -> bool:
    return isinstance(value, (str, Substitution)) or (
        isinstance(value, (list, tuple)) and all(isinstance(v, (str, Substitution)) for v in value))


class ParameterFile:
    """A YAML parameters file; with allow_substs its text may hold `$(...)` substitutions."""

    def __init__(self, param_file: SomeSubstitutionsType | pathlib.Path, *,
                 allow_substs: bool = False) -> None:
        if isinstance(param_file, pathlib.Path):
            param_file = str(param_file)
        self.param_file = normalize_to_list_of_substitutions(param_file)
        self.allow_substs = allow_substs

    def evaluate(self, context: LaunchContext) -> str:
        """The path to pass with --params-file (a substituted copy when allow_substs)."""
        path = perform_substitutions(context, self.param_file)
        if not self.allow_substs:
            return path
        from launch.frontend import parse_substitution

        with open(path, encoding='utf-8') as handle:
            text = perform_substitutions(context, parse_substitution(handle.read()))
        try:
            yaml.safe_load(text)
        except yaml.YAMLError as error:
            raise ValueError(f"parameter file '{path}' is not valid YAML after substitution: "
                             f'{error}') from None
        with tempfile.NamedTemporaryFile('w', prefix='launch_params_', delete=False) as substituted:
            substituted.write(text)
        return substituted.name


class Parameter:
    """One parameter, passed as `-p name:=<yaml value>`."""

    def __init__(self, name: SomeSubstitutionsType, value: Any, *, value_type: Any = None) -> None:
        self.name = normalize_to_list_of_substitutions(name)
        self.value = (value if isinstance(value, ParameterValue)
                      else ParameterValue(value, value_type=value_type))

    def evaluate(self, context: LaunchContext) -> tuple[str, Any]:
        """(name, value) with the substitutions performed and the value typed, for `-p name:=value`."""
        return perform_substitutions(context, self.name), self.value.evaluate(context)
