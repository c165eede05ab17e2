"""Entity of an XML launch file: attributes are strings, nested tags are child elements."""

from __future__ import annotations

from typing import Any

from launch.frontend.entity import Entity as BaseEntity


class Entity(BaseEntity):
    """An XML element; its child elements are its nested tags and, in a container, its actions."""

    is_xml = True

    def __init__(self, type_name: str, attributes: dict[str, Any], elements: list[Entity], file: str,
                 line: int | None) -> None:
        super().__init__(type_name, attributes, file, line)
        self._elements = elements
        self._used_tags: set[str] = set()

    def get_children(self, tag: str) -> list[BaseEntity]:
        """Nested tags of one kind (`param`, `remap`, `env`, `arg`, `keep`, `choice`...)."""
        self._used_tags.add(tag)
        return [element for element in self._elements if element.type_name == tag]

    def action_children(self) -> list[BaseEntity]:
        """The actions inside a container tag (launch, group, timer)."""
        children = [e for e in self._elements if e.type_name not in self._used_tags]
        self._used_tags.update(e.type_name for e in children)
        return list(children)

    def assert_entity_completely_parsed(self) -> None:
        super().assert_entity_completely_parsed()
        nested = {e.type_name for e in self._elements} - self._used_tags
        if nested:
            raise self.error(f'Unexpected nested tag(s) found in `{self.type_name}`: {nested}')
