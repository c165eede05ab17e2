"""Node parameters for the command line: dicts flattened to dotted names, files, YAML text.

The values themselves are typed by launch_ros.parameter_descriptions.evaluate_value.
"""

from __future__ import annotations

import tempfile
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import yaml
from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

from launch_ros.parameter_descriptions import evaluate_value

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


def flatten_parameters(context: LaunchContext, parameters: Mapping[Any, Any],
                       prefix: str = '') -> dict[str, Any]:
    """Nested dicts become dotted names; keys may be substitutions; values are evaluated."""
    flat: dict[str, Any] = {}
    for key, value in parameters.items():
        name = key if isinstance(key, str) else perform_substitutions(
            context, normalize_to_list_of_substitutions(key))
        full_name = f'{prefix}.{name}' if prefix else name
        if isinstance(value, Mapping):
            flat.update(flatten_parameters(context, value, full_name))
        else:
            flat[full_name] = evaluate_value(context, value, full_name)
    return flat


def write_parameters_file(node_key: str, parameters: dict[str, Any]) -> str:
    """A temporary launch_params_* YAML file {node_key: {ros__parameters: ...}}; kept after launch."""
    with tempfile.NamedTemporaryFile('w', prefix='launch_params_', delete=False) as handle:
        yaml.safe_dump({node_key: {'ros__parameters': parameters}}, handle, default_flow_style=False)
    return handle.name


def yaml_text(value: Any) -> str:
    """A value as YAML text for `-p name:=value`."""
    return yaml.safe_dump(value, default_flow_style=True).removesuffix('\n...\n').strip()
