"""Upstream's type names for Node(parameters=...): as given, normalised, and evaluated."""

from __future__ import annotations

import pathlib
from collections.abc import Mapping, Sequence
from typing import Any

from launch.some_substitutions_type import SomeSubstitutionsType, SomeSubstitutionsType_types_tuple
from launch.substitution import Substitution

from launch_ros.parameter_descriptions import Parameter, ParameterFile, ParameterValue

__all__ = [
    'EvaluatedParameterValue', 'EvaluatedParameters', 'ParameterFile', 'ParameterName',
    'Parameters', 'ParametersDict', 'SomeParameterFile', 'SomeParameterName', 'SomeParameterValue',
    'SomeParameterValue_types_tuple', 'SomeParameters', 'SomeParametersDict',
]

_Scalar = str | int | float | bool
_MultiValue = Sequence[str] | Sequence[int] | Sequence[float] | Sequence[bool] | bytes

# What a user passes.
SomeParameterFile = SomeSubstitutionsType | pathlib.Path | ParameterFile
SomeParameterName = SomeSubstitutionsType
SomeParameterValue = (ParameterValue | SomeSubstitutionsType | Sequence[SomeSubstitutionsType] | _Scalar
                      | _MultiValue)
# The types isinstance can check a single value against (sequences are checked item by item).
SomeParameterValue_types_tuple = (*SomeSubstitutionsType_types_tuple, str, int, float, bool, bytes)
# {name: value}, nested dicts giving dotted names.
SomeParametersDict = Mapping[SomeParameterName, Any]
SomeParameters = Sequence[SomeParametersDict | SomeParameterFile | Parameter]

# What normalize_parameters makes of them: names are tuples of substitutions, nested dicts flattened.
ParameterName = Sequence[Substitution]
ParametersDict = dict[tuple[Substitution, ...], Any]
Parameters = Sequence[ParametersDict | ParameterFile | Parameter]

# What evaluate_parameters makes of those: text names, typed values (sequences as tuples), file paths.
EvaluatedParameterValue = _Scalar | _MultiValue
EvaluatedParameters = Sequence[pathlib.Path | Parameter | dict[str, EvaluatedParameterValue]]
