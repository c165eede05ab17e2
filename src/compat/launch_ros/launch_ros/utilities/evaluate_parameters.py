"""Node parameters evaluated in a launch context: dicts of values, and parameter file paths."""

from __future__ import annotations

import pathlib
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

from launch_ros.parameter_descriptions import Parameter, ParameterFile
from launch_ros.parameters import flatten_parameters

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext

__all__ = ['evaluate_parameters']


def evaluate_parameters(context: LaunchContext, parameters: Iterable[Any]) -> list[Any]:
    """Each dict becomes {dotted name: value}, each Parameter a one-entry dict, each file its path."""
    evaluated: list[Any] = []
    for item in parameters:
        if isinstance(item, dict):
            evaluated.append(flatten_parameters(context, item))
        elif isinstance(item, Parameter):
            name, value = item.evaluate(context)
            evaluated.append({name: value})
        elif isinstance(item, ParameterFile):
            evaluated.append(pathlib.Path(item.evaluate(context)))
        else:
            path = str(item) if isinstance(item, pathlib.Path) else item
            evaluated.append(pathlib.Path(perform_substitutions(
                context, normalize_to_list_of_substitutions(path))))
    return evaluated
