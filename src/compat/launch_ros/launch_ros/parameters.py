"""How node parameters become values: the typing rules of upstream launch_ros.

Python values are kept (a literal str stays a string); a substitution is performed and its text
read as YAML ('200' is an int, 'true' a bool, '1.0' a float, '[1, 2]' a list).
"""

from __future__ import annotations

import tempfile
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any, get_args, get_origin

import yaml
from launch.substitution import Substitution, normalize_to_list_of_substitutions, perform_substitutions

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext

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
    from launch_ros.parameter_descriptions import ParameterValue

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
