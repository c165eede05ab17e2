"""One tag of an XML or YAML launch file, with strict accounting of what its parser used.

XML: attributes are strings; nested tags are child elements.  YAML: a tag is a single-key
mapping `{tag: value}`; value is a mapping of attributes (nested tags are lists under their tag
name, e.g. `param: [...]`, and actions under `children`) or, for containers, the list of actions.
"""

from __future__ import annotations

from typing import Any
from xml.parsers import expat

import yaml


class LaunchFileError(ValueError):
    """A mistake in an XML or YAML launch file; the message starts with file:line."""


class Entity:
    def __init__(self, type_name: str, attributes: dict[str, Any], elements: list[Entity] | None,
                 file: str, line: int | None, is_xml: bool,
                 yaml_children: list[Any] | None = None) -> None:
        self.type_name = type_name
        self._yaml_children = yaml_children
        self._attributes = attributes
        self._elements = elements
        self.file = file
        self.line = line
        self.is_xml = is_xml
        self._used_attributes: set[str] = set()
        self._used_tags: set[str] = set()

    @property
    def location(self) -> str:
        return f'{self.file}:{self.line}' if self.line is not None else self.file

    def error(self, message: str) -> LaunchFileError:
        return LaunchFileError(f'{self.location}: {message}')

    def get_attr(self, name: str, *, optional: bool = False) -> Any:
        """The raw value: a str in XML, any YAML value in YAML; None if optional and absent."""
        self._used_attributes.add(name)
        if name in self._attributes:
            return self._attributes[name]
        if optional:
            return None
        raise self.error(f"Attribute '{name}' of type '{self.type_name}' not found")

    def get_children(self, tag: str) -> list[Entity]:
        """Nested tags of one kind (`param`, `remap`, `env`, `arg`, `keep`, `choice`...)."""
        if self.is_xml:
            self._used_tags.add(tag)
            return [element for element in self._elements or [] if element.type_name == tag]
        items = self.get_attr(tag, optional=True)
        if items is None:
            return []
        if not isinstance(items, list):
            raise self.error(f"'{tag}' of `{self.type_name}` must be a list")
        return [_yaml_item(tag, item, self.file, self._line_of(item)) for item in items]

    def action_children(self) -> list[Entity]:
        """The actions inside a container tag (launch, group, timer)."""
        if self.is_xml:
            children = [e for e in self._elements or [] if e.type_name not in self._used_tags]
            self._used_tags.update(e.type_name for e in children)
            return children
        items = self._yaml_children
        if items is None:
            items = self.get_attr('children', optional=True) or []
        if not isinstance(items, list):
            raise self.error(f"the children of `{self.type_name}` must be a list")
        return [_yaml_entity(item, self.file) for item in items]

    def _line_of(self, item: Any) -> int | None:
        return getattr(item, 'line', self.line)

    def assert_entity_completely_parsed(self) -> None:
        unexpected = set(self._attributes) - self._used_attributes
        if unexpected:
            kind = 'attribute(s)' if self.is_xml else 'key(s)'
            raise self.error(f'Unexpected {kind} found in `{self.type_name}`: {unexpected}')
        if self.is_xml:
            nested = {e.type_name for e in self._elements or []} - self._used_tags
            if nested:
                raise self.error(f'Unexpected nested tag(s) found in `{self.type_name}`: {nested}')


class _LineDict(dict):
    line: int | None = None


class _LineLoader(yaml.SafeLoader):
    """A YAML loader whose mappings remember the line they start on."""


def _construct_mapping(loader: _LineLoader, node: yaml.MappingNode) -> _LineDict:
    mapping = _LineDict(loader.construct_mapping(node, deep=True))
    mapping.line = node.start_mark.line + 1
    return mapping


_LineLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _construct_mapping)


def _yaml_item(tag: str, value: Any, file: str, line: int | None) -> Entity:
    """A nested tag in YAML: its value is the mapping of its attributes."""
    if not isinstance(value, dict):
        raise LaunchFileError(f'{file}:{line}: each `{tag}` must be a mapping, got {value!r}')
    return Entity(tag, value, None, file, getattr(value, 'line', line), is_xml=False)


def _yaml_entity(item: Any, file: str) -> Entity:
    """An action in YAML: a single-key mapping {tag: attributes-or-list-of-children}."""
    line = getattr(item, 'line', None)
    if not isinstance(item, dict) or len(item) != 1:
        raise LaunchFileError(f'{file}:{line}: expected a single-key mapping like `- node: {{...}}`, '
                              f'got {item!r}')
    [(tag, value)] = item.items()
    if isinstance(value, list):
        return Entity(tag, {}, None, file, line, is_xml=False, yaml_children=value)
    if value is None:
        value = {}
    if not isinstance(value, dict):
        raise LaunchFileError(f'{file}:{line}: the value of `{tag}` must be a mapping, got {value!r}')
    return Entity(tag, value, None, file, line, is_xml=False)


def load_yaml_root(path: str) -> Entity:
    with open(path, encoding='utf-8') as handle:
        try:
            document = yaml.load(handle, Loader=_LineLoader)
        except yaml.YAMLError as error:
            raise LaunchFileError(f'{path}: invalid YAML: {error}') from None
    if not isinstance(document, dict) or len(document) != 1:
        raise LaunchFileError(f'{path}: Expected only one root')
    if 'launch' not in document:
        raise LaunchFileError(f"{path}: Expected 'launch' as root tag")
    return _yaml_entity(document, path)


def load_xml_root(path: str) -> Entity:
    """Parse with expat directly, which knows the line of every element."""
    parser = expat.ParserCreate()
    stack: list[Entity] = []
    roots: list[Entity] = []

    def start(tag: str, attributes: dict[str, str]) -> None:
        entity = Entity(tag, attributes, [], path, parser.CurrentLineNumber, is_xml=True)
        (stack[-1]._elements if stack else roots).append(entity)  # type: ignore[union-attr]
        stack.append(entity)

    def end(_tag: str) -> None:
        stack.pop()

    parser.StartElementHandler = start
    parser.EndElementHandler = end
    with open(path, 'rb') as handle:
        try:
            parser.ParseFile(handle)
        except expat.ExpatError as error:
            raise LaunchFileError(f'{path}:{error.lineno}: invalid XML: '
                                  f'{expat.ErrorString(error.code)}') from None
    root = roots[0]
    if root.type_name != 'launch':
        raise LaunchFileError(f"{path}: Expected 'launch' as root tag")
    return root
