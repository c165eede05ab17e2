"""Node parameters checked and normalised: names to substitutions, files to ParameterFile.

The normalised form is upstream's: a tuple whose items are ParameterFile, Parameter, or a flat dict
{tuple of name substitutions: value} (nested dicts joined with '.'), read back by evaluate_parameters.
"""

from __future__ import annotations

import pathlib
from collections.abc import Mapping, Sequence
from typing import Any

import yaml
from launch.substitution import Substitution
from launch.substitutions import TextSubstitution
from launch.utilities import normalize_to_list_of_substitutions

from launch_ros.parameter_descriptions import Parameter, ParameterFile, ParameterValue
from launch_ros.parameters_type import Parameters, ParametersDict

__all__ = ['check_parameters_item', 'normalize_parameter_dict', 'normalize_parameters']


def check_parameters_item(item: Any) -> None:
    """One item of Node(parameters=[...]): a dict, a parameter file path or a Parameter object.

    A bare value such as 5.0 has no name to be the value of: refused at construction, as upstream.
    """
    if isinstance(item, (dict, Parameter, ParameterFile, str, Substitution, pathlib.Path)):
        return
    if isinstance(item, (list, tuple)) and item and all(isinstance(i, (str, Substitution)) for i in item):
        return  # a path made of text and substitutions
    raise TypeError(f"Node parameters must be dicts, parameter file paths or Parameter objects, got "
                    f"{item!r} ('{type(item).__name__}')")


def _quoted(value: str | bool | int | float) -> tuple[Substitution, ...]:
    """Text that evaluate_parameters reads back (as YAML) into this very value: '5' stays a string."""
    return (TextSubstitution(text=yaml.safe_dump(value)),)


def _normalize_sequence(name: str, value: Sequence[Any]) -> tuple[Any, ...]:
    """A list value, as a tuple whose shape evaluate_parameters reads back.

    Numbers and bools keep their type, text and substitutions side by side make one string, anything
    else becomes one substitution tuple per item (a list of strings).
    """
    kinds: set[type] = set()
    for item in value:
        if isinstance(item, Substitution):
            kinds.add(Substitution)
        elif isinstance(item, (str, bool, int, float)):
            kinds.add(type(item))
        elif isinstance(item, Sequence) and not isinstance(item, bytes):
            kinds.add(tuple)
        else:
            raise TypeError(f"parameter '{name}': list items must be text, numbers, bools or substitutions, "
                            f"got {item!r} ('{type(item).__name__}')")
    if kinds == {int}:
        return tuple(value)
    if kinds in ({float}, {int, float}):
        return tuple(float(item) for item in value)
    if kinds == {bool}:
        return tuple(value)
    if Substitution in kinds and kinds <= {str, Substitution}:
        return tuple(normalize_to_list_of_substitutions(value))
    return tuple(_quoted(item) if isinstance(item, (str, bool, int, float))
                 else tuple(normalize_to_list_of_substitutions(item)) for item in value)


def normalize_parameter_dict(parameters: Mapping[Any, Any], *,
                             _prefix: Sequence[Substitution] | None = None) -> ParametersDict:
    """A {name: value} dict flattened (nested dicts give 'outer.inner' names), names as substitution tuples.

    Literal text is kept so that it evaluates to the same string; a substitution is read as YAML once
    performed; numbers, bools, bytes and ParameterValue are kept as they are; TypeError for other values.
    """
    if not isinstance(parameters, Mapping):
        raise TypeError(f"parameters must be a dict, got '{type(parameters).__name__}': {parameters!r}")
    normalized: ParametersDict = {}
    for key, value in parameters.items():
        name = normalize_to_list_of_substitutions(key)
        if _prefix:
            name = [*_prefix, TextSubstitution(text='.'), *name]
        if isinstance(value, Mapping):
            normalized.update(normalize_parameter_dict(value, _prefix=name))
        elif isinstance(value, (ParameterValue, bool, int, float, bytes)):
            normalized[tuple(name)] = value
        elif isinstance(value, str):
            normalized[tuple(name)] = _quoted(value)
        elif isinstance(value, Substitution):
            normalized[tuple(name)] = (value,)
        elif isinstance(value, Sequence):
            normalized[tuple(name)] = _normalize_sequence(str(key), value)
        else:
            raise TypeError(f"Unexpected type for parameter '{key}': {value!r} ('{type(value).__name__}')")
    return normalized


def normalize_parameters(parameters: Sequence[Any]) -> Parameters:
    """The items of Node(parameters=[...]) normalised, as a tuple.

    Dicts go through normalize_parameter_dict, Parameter and ParameterFile stay, and anything else must
    be a parameter file path (TypeError otherwise, e.g. for a bare value such as 5.0).
    """
    if isinstance(parameters, str) or not isinstance(parameters, Sequence):
        raise TypeError(f'parameters must be a list, got {type(parameters).__name__!r}: {parameters!r}')
    normalized: list[ParametersDict | ParameterFile | Parameter] = []
    for item in parameters:
        if isinstance(item, Mapping):
            normalized.append(normalize_parameter_dict(item))
        elif isinstance(item, (Parameter, ParameterFile)):
            normalized.append(item)
        else:
            check_parameters_item(item)
            normalized.append(ParameterFile(item))
    return tuple(normalized)
