"""Evaluated node parameters as rclpy Parameter objects (what a LoadNode request carries)."""

from __future__ import annotations

import pathlib
import warnings
from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING, Any

import rclpy.parameter
import yaml

from launch_ros.parameter_descriptions import Parameter
from launch_ros.utilities.evaluate_parameters import evaluate_parameter_dict
from launch_ros.utilities.normalize_parameters import normalize_parameter_dict

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext

__all__ = ['to_parameters_list']


def _sections_by_node(document: Mapping[Any, Any]) -> dict[str, dict[str, Any]]:
    """The ros__parameters sections of a parameter file, by the keys above them joined with '/'.

    Leading '/' are dropped: '/**' is '**', '/ns/talker' is 'ns/talker'.
    """
    sections: dict[str, dict[str, Any]] = {}

    def walk(mapping: Mapping[Any, Any], path: list[str]) -> None:
        for key, value in mapping.items():
            if key == 'ros__parameters':
                sections['/'.join(path)] = value
                return
            if isinstance(value, Mapping):
                walk(value, [*path, str(key).lstrip('/')])

    walk(document, [])
    return sections


def _file_parameters(context: LaunchContext, path: pathlib.Path, node_key: str) -> dict[str, Any]:
    """The parameters a file gives the node: its '/**' section, then its own (which wins).

    A file with no ros__parameters section at all is read as plain {name: value}.
    """
    with open(path, encoding='utf-8') as handle:
        document = yaml.safe_load(handle) or {}
    if not isinstance(document, Mapping):
        raise RuntimeError(f"parameter file '{path}' does not hold a mapping")
    sections = _sections_by_node(document)
    if not sections:
        values: Mapping[Any, Any] = document
    else:
        if not node_key:
            warnings.warn('node name not provided to launch; parameter files will not apply', UserWarning,
                          stacklevel=3)
        values = {**sections.get('**', {}), **sections.get(node_key, {})}
    return evaluate_parameter_dict(context, normalize_parameter_dict(values)) if values else {}


def to_parameters_list(context: LaunchContext, node_name: str, namespace: str | None,
                       evaluated_parameters: Iterable[Any]) -> list[rclpy.parameter.Parameter]:
    """Evaluated parameters (see evaluate_parameters) as rclpy Parameters, in order.

    A file contributes the sections for '/**' and for the node (namespace/node_name); a dict each of
    its entries; a Parameter description its (name, value). The type of each is the ROS one its value
    has; RuntimeError for an item or a value that fits none.
    """
    node_key = node_name.lstrip('/')
    if namespace and namespace != '/':
        node_key = f"{namespace.strip('/')}/{node_key}"
    parameters: list[rclpy.parameter.Parameter] = []
    for item in evaluated_parameters:
        if isinstance(item, pathlib.Path):
            values = _file_parameters(context, item, node_key)
        elif isinstance(item, Parameter):
            name, value = item.evaluate(context)
            values = {name: value}
        elif isinstance(item, dict):
            values = item
        else:
            raise RuntimeError(f'invalid evaluated parameters {item!r}: expected a file path, a dict or a '
                               'Parameter (see launch_ros.utilities.evaluate_parameters)')
        for name, value in values.items():
            kind = next((kind for kind in rclpy.parameter.Parameter.Type if kind.check(value)), None)
            if kind is None:
                raise RuntimeError(f"invalid value {value!r} for parameter '{name}'")
            parameters.append(rclpy.parameter.Parameter(name, kind, value))
    return parameters
