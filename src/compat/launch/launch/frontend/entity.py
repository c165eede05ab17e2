"""One tag of a launch file, with strict accounting of what its action's parser used.

The frontend parsers (launch_xml, launch_yaml) read a file into entities of their own Entity
subclass: attributes and the file:line of the tag are kept here, while how nested tags and child
actions are written is the format's.
"""

from __future__ import annotations

from typing import Any, get_args, get_origin

from launch.utilities.type_utils import get_typed_value, is_instance_of

# get_attr's data_type when none is given: the value as the file has it.
_RAW = object()


class LaunchFileError(ValueError):
    """A mistake in an XML or YAML launch file; the message starts with file:line."""


class Entity:
    """A tag: its type (`node`, `group`...), its attributes and where it is written."""

    # Whether the tag comes from an XML file (its errors say attributes, YAML's say keys).
    is_xml = False

    def __init__(self, type_name: str, attributes: dict[str, Any], file: str, line: int | None,
                 parent: Entity | None = None) -> None:
        self.type_name = type_name
        self._attributes = attributes
        self.file = file
        self.line = line
        self.parent = parent
        self._used_attributes: set[str] = set()

    @property
    def children(self) -> list[Entity]:
        """The actions inside this tag, as upstream's Entity.children gives them."""
        return self.action_children()

    @property
    def location(self) -> str:
        return f'{self.file}:{self.line}' if self.line is not None else self.file

    def error(self, message: str) -> LaunchFileError:
        return LaunchFileError(f'{self.location}: {message}')

    def get_attr(self, name: str, *, data_type: Any = _RAW, optional: bool = False,
                 can_be_str: bool = True) -> Any:
        """An attribute's value; None if optional and absent.

        Without data_type, the raw value: a str in XML, any YAML value in YAML.  With data_type
        (one of type_utils' types, None for "whatever YAML reads"), text is converted to it as
        upstream's frontends do; can_be_str keeps text that does not convert (it may hold a
        `$(...)`, see Parser.parse_if_substitutions).
        """
        if _is_entity_list(data_type):
            # Upstream's way for an action's parser to read nested tags: get_attr('remap', List[Entity]).
            nested = self.get_children(name)
            if nested or optional:
                return nested or None
            raise self.error(f"Nested tag '{name}' of type '{self.type_name}' not found")
        self._used_attributes.add(name)
        if name not in self._attributes:
            if optional:
                return None
            raise self.error(f"Attribute '{name}' of type '{self.type_name}' not found")
        value = self._attributes[name]
        if data_type is _RAW:
            return value
        try:
            if isinstance(value, str) or (isinstance(value, list)
                                          and all(isinstance(item, str) for item in value)):
                return get_typed_value(value, data_type, can_be_str)
            if is_instance_of(value, data_type, can_be_str):
                return value
            if data_type is float and isinstance(value, int) and not isinstance(value, bool):
                return float(value)  # YAML's `period: 2` is a float attribute's 2.0
        except (TypeError, ValueError) as error:
            raise self.error(f"attribute '{name}' of `{self.type_name}`: {error}") from None
        raise self.error(f"attribute '{name}' of `{self.type_name}` must be of type "
                         f"{getattr(data_type, '__name__', data_type)}, got {value!r}")

    def get_children(self, tag: str) -> list[Entity]:
        """Nested tags of one kind (`param`, `remap`, `env`, `arg`, `keep`, `choice`...)."""
        raise NotImplementedError(type(self).__name__)

    def action_children(self) -> list[Entity]:
        """The actions inside a container tag (launch, group, timer)."""
        raise NotImplementedError(type(self).__name__)

    def assert_entity_completely_parsed(self) -> None:
        unexpected = set(self._attributes) - self._used_attributes
        if unexpected:
            kind = 'attribute(s)' if self.is_xml else 'key(s)'
            raise self.error(f'Unexpected {kind} found in `{self.type_name}`: {unexpected}')


def _is_entity_list(data_type: Any) -> bool:
    """Whether data_type is List[Entity] or list[Entity] (of this Entity or a frontend's subclass)."""
    if get_origin(data_type) is not list:  # typing.List[X] has list as its origin too
        return False
    args = get_args(data_type)
    return len(args) == 1 and isinstance(args[0], type) and issubclass(args[0], Entity)
