"""Node parameters checked and normalised at construction."""

from __future__ import annotations

import pathlib
from collections.abc import Iterable
from typing import Any

from launch.substitution import Substitution

from launch_ros.parameter_descriptions import Parameter, ParameterFile

__all__ = ['check_parameters_item', 'normalize_parameters']


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


def normalize_parameters(parameters: Iterable[Any]) -> list[Any]:
    """The items of Node(parameters=...) after checking each (a bare value is a TypeError)."""
    if isinstance(parameters, (str, dict)):
        raise TypeError(f"parameters must be a list, got '{type(parameters).__name__}'")
    items = list(parameters)
    for item in items:
        check_parameters_item(item)
    return items
