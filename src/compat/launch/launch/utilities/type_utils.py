"""Typed values of launch: text read with YAML's rules, as upstream launch types its attributes.

A typed value is `str`, `int`, `float`, `bool` or a uniform list of one of them.  Text becomes a
bool, a number or a list the way a YAML 1.1 reader sees it, so 'yes', 'on', 'true' are True and
'no', 'off', 'false' are False (that is what upstream's `<node respawn="yes">` accepts).  Read as a
bool, '1' and '0' are True and False too, as in Jazzy; read untyped, '1' is the integer 1.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from types import GenericAlias
from typing import TYPE_CHECKING, Any, cast, get_args, get_origin

import yaml

from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext

__all__ = [
    'AllowedTypesTuple', 'AllowedTypesType', 'AllowedValueType', 'ListTypesTuple', 'ListTypesType',
    'ListValueType', 'NormalizedScalarType', 'NormalizedSequenceType', 'NormalizedValueType',
    'ScalarTypesTuple', 'ScalarTypesType', 'ScalarValueType', 'SequenceValueType', 'SomeScalarType',
    'SomeSequenceType', 'SomeValueType', 'StrSomeScalarType', 'StrSomeSequenceType', 'StrSomeValueType',
    'coerce_list', 'coerce_to_type', 'extract_type', 'get_typed_value', 'is_instance_of',
    'is_instance_of_valid_type', 'is_normalized_substitution', 'is_substitution', 'is_typing_list',
    'is_valid_scalar_type', 'normalize_typed_substitution', 'perform_typed_substitution',
]

# The value types a typed launch attribute may have: one scalar, or a list of one scalar type.
ScalarTypesTuple = (int, float, bool, str)
ListTypesTuple = (list[int], list[float], list[bool], list[str])
AllowedTypesTuple = ScalarTypesTuple + ListTypesTuple
ScalarTypesType = type[int] | type[float] | type[bool] | type[str]
# list[int] and the other list types are generic aliases, not classes.
ListTypesType = GenericAlias
AllowedTypesType = type | GenericAlias
# The values themselves, and the same before substitution (Some*), normalized (Normalized*: text
# already a list of substitutions) and as a launch file's text gives them (StrSome*).
ScalarValueType = int | float | bool | str
ListValueType = list[int] | list[float] | list[bool] | list[str]
SequenceValueType = Sequence[int] | Sequence[float] | Sequence[bool] | Sequence[str]
AllowedValueType = ScalarValueType | ListValueType
SomeScalarType = ScalarValueType | SomeSubstitutionsType
SomeSequenceType = (Sequence[int | SomeSubstitutionsType] | Sequence[float | SomeSubstitutionsType]
                    | Sequence[bool | SomeSubstitutionsType] | Sequence[str | SomeSubstitutionsType])
SomeValueType = AllowedValueType | SomeSubstitutionsType
NormalizedScalarType = ScalarValueType | list[Substitution]
NormalizedSequenceType = (list[int | list[Substitution]] | list[float | list[Substitution]]
                          | list[bool | list[Substitution]] | list[str | list[Substitution]])
NormalizedValueType = NormalizedScalarType | NormalizedSequenceType
StrSomeScalarType = SomeScalarType
StrSomeSequenceType = Sequence[int | str] | Sequence[float | str] | Sequence[bool | str] | Sequence[str]
StrSomeValueType = StrSomeScalarType | StrSomeSequenceType

def is_typing_list(data_type: object) -> bool:
    """list, typing.List or a subscription of either (list[int], List[str])."""
    return data_type is list or get_origin(data_type) is list


def is_valid_scalar_type(data_type: object) -> bool:
    return data_type in ScalarTypesTuple


def extract_type(data_type: object) -> tuple[type, bool]:
    """(item type, is it a list) of an allowed type; anything else is a ValueError."""
    is_list = is_typing_list(data_type)
    scalar = (get_args(data_type) or (None,))[0] if is_list else data_type
    if not is_valid_scalar_type(scalar):
        raise ValueError(f'Unrecognized data type: {data_type}')
    return cast(type, scalar), is_list  # one of ScalarTypesTuple, checked above


def is_instance_of_valid_type(value: object, can_be_str: bool = False) -> bool:
    """A scalar of an allowed type, or a list of one such type (strings mixed in if can_be_str)."""
    if not isinstance(value, list):
        return isinstance(value, ScalarTypesTuple)
    kinds = {type(item) for item in value}
    if can_be_str:
        kinds.discard(str)
    return len(kinds) <= 1 and all(kind in ScalarTypesTuple for kind in kinds)


def is_instance_of(value: object, data_type: AllowedTypesType | None = None,
                   can_be_str: bool = False) -> bool:
    if data_type is None:
        return is_instance_of_valid_type(value, can_be_str)
    item_type, is_list = extract_type(data_type)
    accepted: tuple[type, ...] = (str, item_type) if can_be_str else (item_type,)

    def matches(item: object) -> bool:
        # bool is an int subclass in Python, but not an int here
        return isinstance(item, accepted) and not (item_type in (int, float)
                                                   and isinstance(item, bool))
    if not is_list:
        return matches(value)
    return isinstance(value, list) and all(matches(item) for item in value)


def _yaml_reading(text: str, what: str, can_be_str: bool) -> Any:
    try:
        value = yaml.safe_load(text)
    except yaml.YAMLError as error:
        if can_be_str:
            return text
        raise ValueError(f'{what}: it is not valid YAML ({getattr(error, "problem", error)})') from None
    if value is None:
        return text
    if not is_instance_of_valid_type(value, can_be_str):
        raise ValueError(f'{what}: YAML reads it as {type(value).__name__}, which is not a launch value type')
    return value


def coerce_to_type(value: str, data_type: AllowedTypesType | None = None, can_be_str: bool = False
                   ) -> Any:
    """The text `value` as data_type (None: whatever YAML makes of it)."""
    if not isinstance(value, str):
        raise TypeError(f"coerce_to_type expects a str value, got '{type(value).__name__}'")
    if data_type is None:
        return _yaml_reading(value, f"cannot convert '{value}'", can_be_str)
    item_type, is_list = extract_type(data_type)
    if is_list:
        result = _yaml_reading(value, f"cannot convert '{value}' to a list of {item_type.__name__}",
                               can_be_str)
        if not isinstance(result, list) or not is_instance_of(result, data_type, can_be_str):
            raise ValueError(f"cannot convert '{value}' to a list of {item_type.__name__}")
        return result
    if item_type is str:
        return value
    if item_type in (int, float):
        try:
            return item_type(value)
        except ValueError:
            if can_be_str:
                return value
            raise ValueError(f"cannot convert '{value}' to {item_type.__name__}") from None
    # Jazzy reads the digits 1 and 0 as a bool's text, as conditions do
    text = {'1': 'true', '0': 'false'}.get(value, value)
    result = _yaml_reading(text, f"cannot convert '{value}' to bool", can_be_str)
    if isinstance(result, bool) or (can_be_str and isinstance(result, str)):
        return result
    raise ValueError(f"cannot convert '{value}' to bool: expected true/false, 1/0, yes/no or on/off")


def coerce_list(value: list[str], data_type: AllowedTypesType | None = None, can_be_str: bool = False
                ) -> list[Any]:
    if not isinstance(value, list):
        raise TypeError(f"coerce_list expects a list, got '{type(value).__name__}'")
    result = [coerce_to_type(item, data_type, can_be_str) for item in value]
    if not is_instance_of_valid_type(result, can_be_str):
        raise ValueError(f'cannot convert {value} to a uniform list')
    return result


def get_typed_value(value: str | list[str], data_type: AllowedTypesType | None, can_be_str: bool = False
                    ) -> Any:
    """A str or a list of str converted to data_type."""
    if isinstance(value, list):
        item_type = None
        if data_type is not None:
            item_type, is_list = extract_type(data_type)
            if not is_list:
                raise TypeError(f"cannot convert the list {value} to '{item_type.__name__}'")
        return coerce_list(value, item_type, can_be_str)
    return coerce_to_type(value, data_type, can_be_str)


def is_substitution(value: object) -> bool:
    """A Substitution, or a non-empty iterable of str and Substitution with at least one of the latter."""
    if isinstance(value, Substitution):
        return True
    if isinstance(value, (str, bytes)) or not isinstance(value, Iterable):
        return False
    items = list(value)
    return (bool(items) and all(isinstance(item, (str, Substitution)) for item in items)
            and any(isinstance(item, Substitution) for item in items))


def is_normalized_substitution(value: object) -> bool:
    """A non-empty list holding only Substitution instances (what normalizing text gives)."""
    return isinstance(value, list) and bool(value) and all(isinstance(item, Substitution) for item in value)


def normalize_typed_substitution(value: Any, data_type: AllowedTypesType | None) -> Any:
    """A value of data_type stays as it is; text and substitutions become a substitution list.

    Text is kept for later (it is converted when performed); a value of another type is a
    TypeError now, at construction, where the launch file's author can see it.
    """
    if isinstance(value, str) or is_substitution(value):
        return normalize_to_list_of_substitutions(value)
    if isinstance(value, list):
        return [normalize_to_list_of_substitutions(item) if isinstance(item, str) or is_substitution(item)
                else item for item in value]
    if not is_instance_of(value, data_type):
        expected = getattr(data_type, '__name__', str(data_type))
        raise TypeError(f"value {value!r} is not a {expected}")
    return value


def perform_typed_substitution(context: LaunchContext, value: Any, data_type: AllowedTypesType | None
                               ) -> Any:
    """Perform what normalize_typed_substitution kept, then convert it to data_type."""
    if is_normalized_substitution(value):
        return coerce_to_type(perform_substitutions(context, value), data_type)
    if isinstance(value, list):
        item_type = None
        if data_type is not None:
            item_type, is_list = extract_type(data_type)
            if not is_list:
                raise ValueError(f'cannot convert the list {value!r} to a single {item_type.__name__}')
        items = [perform_substitutions(context, item) if isinstance(item, list) else item
                 for item in value]
        return [coerce_to_type(item, item_type) if isinstance(item, str) and item_type is not str
                else item for item in items]
    return value
