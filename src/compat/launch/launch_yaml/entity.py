"""Entity of a YAML launch file.

A tag is a single-key mapping `{tag: value}`; value is a mapping of attributes (nested tags are
lists under their tag name, e.g. `param: [...]`, and actions under `children`) or, for containers,
the list of actions.
"""

from __future__ import annotations

from typing import Any

from launch.frontend.entity import Entity as BaseEntity
from launch.frontend.entity import LaunchFileError


class Entity(BaseEntity):
    """A YAML tag; the mappings the YAML reader made remember their line (`.line`)."""

    def __init__(self, type_name: str, attributes: dict[str, Any], file: str, line: int | None,
                 yaml_children: list[Any] | None = None) -> None:
        super().__init__(type_name, attributes, file, line)
        self._yaml_children = yaml_children

    def get_children(self, tag: str) -> list[BaseEntity]:
        """Nested tags of one kind (`param`, `remap`, `env`, `arg`, `keep`, `choice`...)."""
        items = self.get_attr(tag, optional=True)
        if items is None:
            return []
        if not isinstance(items, list):
            raise self.error(f"'{tag}' of `{self.type_name}` must be a list")
        nested: list[BaseEntity] = [_yaml_item(tag, item, self.file, self._line_of(item)) for item in items]
        for entity in nested:
            entity.parent = self
        return nested

    def action_children(self) -> list[BaseEntity]:
        """The actions inside a container tag (launch, group, timer)."""
        items = self._yaml_children
        if items is None:
            items = self.get_attr('children', optional=True) or []
        if not isinstance(items, list):
            raise self.error(f"the children of `{self.type_name}` must be a list")
        children: list[BaseEntity] = [yaml_entity(item, self.file) for item in items]
        for child in children:
            child.parent = self
        return children

    def _line_of(self, item: Any) -> int | None:
        return getattr(item, 'line', self.line)


def _yaml_item(tag: str, value: Any, file: str, line: int | None) -> Entity:
    """A nested tag in YAML: its value is the mapping of its attributes."""
    if not isinstance(value, dict):
        raise LaunchFileError(f'{file}:{line}: each `{tag}` must be a mapping, got {value!r}')
    return Entity(tag, value, file, getattr(value, 'line', line))


def yaml_entity(item: Any, file: str) -> Entity:
    """An action in YAML: a single-key mapping {tag: attributes-or-list-of-children}."""
    line = getattr(item, 'line', None)
    if not isinstance(item, dict) or len(item) != 1:
        raise LaunchFileError(f'{file}:{line}: expected a single-key mapping like `- node: {{...}}`, '
                              f'got {item!r}')
    [(tag, value)] = item.items()
    if isinstance(value, list):
        return Entity(tag, {}, file, line, yaml_children=value)
    if value is None:
        value = {}
    if not isinstance(value, dict):
        raise LaunchFileError(f'{file}:{line}: the value of `{tag}` must be a mapping, got {value!r}')
    return Entity(tag, value, file, line)
