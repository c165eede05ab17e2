"""Descriptions of node parameters (a value with a forced type, a parameter file, one parameter).

With them, the typing rules of upstream launch_ros by which parameters become values: Python values
are kept (a literal str stays a string); a substitution is performed and its text read as YAML
('200' is an int, 'true' a bool, '1.0' a float, '[1, 2]' a list).
"""

from __future__ import annotations

import pathlib
import tempfile
from typing import TYPE_CHECKING, Any, get_args, get_origin

import yaml
from launch.frontend import parse_substitution
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution
from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

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
        self.__substituted_copy: pathlib.Path | None = None

    def evaluate(self, context: LaunchContext) -> pathlib.Path:
        """The path to pass with --params-file (a substituted copy when allow_substs)."""
        path = perform_substitutions(context, self.param_file)
        if not self.allow_substs:
            return pathlib.Path(path)
        with open(path, encoding='utf-8') as handle:
            text = perform_substitutions(context, parse_substitution(handle.read()))
        try:
            yaml.safe_load(text)
        except yaml.YAMLError as error:
            raise ValueError(f"parameter file '{path}' is not valid YAML after substitution: "
                             f'{error}') from None
        with tempfile.NamedTemporaryFile('w', prefix='launch_params_', delete=False) as substituted:
            substituted.write(text)
        self.__substituted_copy = pathlib.Path(substituted.name)
        return self.__substituted_copy

    def cleanup(self) -> None:
        """Delete the substituted copy the last evaluate made, if any (the file itself is never touched)."""
        if self.__substituted_copy is not None:
            self.__substituted_copy.unlink(missing_ok=True)
            self.__substituted_copy = None


class Parameter:
    """One parameter, passed as `-p name:=<yaml value>`."""

    def __init__(self, name: SomeSubstitutionsType, value: Any, *, value_type: Any = None) -> None:
        self.name = normalize_to_list_of_substitutions(name)
        self.__parameter_value = (value if isinstance(value, ParameterValue)
                                  else ParameterValue(value, value_type=value_type))

    @property
    def value(self) -> Any:
        """The value as given (substitutions not performed)."""
        return self.__parameter_value.value

    @property
    def value_type(self) -> Any:
        """The type the value is forced to, or None for YAML's reading."""
        return self.__parameter_value.value_type

    def evaluate(self, context: LaunchContext) -> tuple[str, Any]:
        """(name, value) with the substitutions performed and the value typed, for `-p name:=value`."""
        return perform_substitutions(context, self.name), self.__parameter_value.evaluate(context)


# ---- the typing rules: how a value given for a parameter becomes the value the node gets ----
SCALARS = (bool, int, float, str, bytes)


def yaml_value(text: str, name: str = '') -> Any:
    """The YAML reading of a performed substitution; only scalars and uniform lists."""
    if text == '':
        return ''
    try:
        value = yaml.safe_load(text)
    except yaml.YAMLError:
        raise TypeError(f'Unable to parse the value of parameter {name} as yaml. If the parameter is '
                        'meant to be a string, try wrapping it in '
                        'launch_ros.parameter_descriptions.ParameterValue(value, value_type=str)') from None
    if value is None:
        return text
    if isinstance(value, list):
        return uniform_list(value, name)
    if not isinstance(value, SCALARS):
        raise TypeError(f"Allowed value types are bytes, bool, int, float, str, and lists of these; "
                        f"parameter '{name}' got {type(value).__name__}. Use "
                        'ParameterValue(value, value_type=str) to pass it as a string.')
    return value


def uniform_list(items: list[Any], name: str = '') -> list[Any]:
    """Lists must hold one type; ints mixed with floats become floats."""
    if not items:
        return items
    if all(isinstance(v, bool) for v in items) or all(isinstance(v, str) for v in items):
        return items
    if all(isinstance(v, int) and not isinstance(v, bool) for v in items):
        return items
    if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in items):
        return [float(v) for v in items]
    raise TypeError(f"Expected a non-empty sequence of one type for parameter '{name}', got {items!r}")


def evaluate_value(context: LaunchContext, value: Any, name: str = '') -> Any:
    """A parameter value as the node gets it: see the module's rules; name is only for error messages.

    Substitutions are performed and read as YAML, text and substitutions side by side make one string,
    lists must be uniform; TypeError for any other type.
    """
    if isinstance(value, ParameterValue):
        return value.evaluate(context)
    if isinstance(value, Substitution):
        return yaml_value(perform_substitutions(context, [value]), name)
    if isinstance(value, (list, tuple)):
        if any(isinstance(v, Substitution) for v in value) and all(
                isinstance(v, (str, Substitution)) for v in value):
            # Text and substitutions side by side are one string.
            return yaml_value(perform_substitutions(context, normalize_to_list_of_substitutions(value)), name)
        return uniform_list([evaluate_value(context, v, name) for v in value], name)
    if isinstance(value, SCALARS):
        return value
    raise TypeError(f"Unsupported type '{type(value).__name__}' for parameter '{name}'")


def coerce_value(value: Any, value_type: Any) -> Any:
    """Force a value to a type: str, int, float, bool or List[...] of those."""
    if get_origin(value_type) in (list, list.__class__) or value_type is list:
        [item_type] = get_args(value_type) or [None]
        items = value if isinstance(value, list) else [value]
        return [coerce_value(v, item_type) if item_type else v for v in items]
    if value_type is str:
        return value if isinstance(value, str) else yaml.safe_dump(value).removesuffix('\n...\n').strip()
    if value_type is bool and not isinstance(value, bool):
        raise TypeError(f'expected a bool value, got {value!r}')
    try:
        return value_type(value)
    except (TypeError, ValueError):
        raise TypeError(f"value {value!r} cannot be a '{value_type.__name__}'") from None
