"""Upstream's type names for Node(parameters=...)."""

from __future__ import annotations

import pathlib
from collections.abc import Mapping, Sequence
from typing import Any

from launch.some_substitutions_type import SomeSubstitutionsType

from launch_ros.parameter_descriptions import Parameter, ParameterFile, ParameterValue

__all__ = [
    'Parameters', 'SomeParameterFile', 'SomeParameterName', 'SomeParameterValue', 'SomeParameters',
]

SomeParameterFile = SomeSubstitutionsType | pathlib.Path | ParameterFile
SomeParameterName = SomeSubstitutionsType
SomeParameterValue = Any | ParameterValue
# One item: {name: value} (nested dicts for dotted names), a parameter file, or a Parameter.
SomeParameters = Sequence[Mapping[SomeParameterName, Any] | SomeParameterFile | Parameter]
Parameters = SomeParameters
