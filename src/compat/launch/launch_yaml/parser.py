"""Parser of YAML launch files (the `yaml` entry of the group 'launch.frontend.parser')."""

from __future__ import annotations

import yaml
from launch.frontend.entity import LaunchFileError
from launch.frontend.parser import Parser as BaseParser

from launch_yaml.entity import Entity, yaml_entity


class _LineDict(dict):
    line: int | None = None


class _LineLoader(yaml.SafeLoader):
    """A YAML loader whose mappings remember the line they start on."""


def _construct_mapping(loader: _LineLoader, node: yaml.MappingNode) -> _LineDict:
    mapping = _LineDict(loader.construct_mapping(node, deep=True))
    mapping.line = node.start_mark.line + 1
    return mapping


_LineLoader.add_constructor(yaml.resolver.BaseResolver.DEFAULT_MAPPING_TAG, _construct_mapping)


class Parser(BaseParser):
    """Reads `.yaml` and `.yml` launch files."""

    @classmethod
    def get_file_extensions(cls) -> set[str]:
        """The file extensions of YAML launch files."""
        return {'yaml', 'yml'}

    @classmethod
    def _load_root(cls, path: str) -> Entity:
        """The `launch` mapping of the file, its mappings knowing their lines."""
        with open(path, encoding='utf-8') as handle:
            try:
                document = yaml.load(handle, Loader=_LineLoader)
            except yaml.YAMLError as error:
                raise LaunchFileError(f'{path}: invalid YAML: {error}') from None
        if not isinstance(document, dict) or len(document) != 1:
            raise LaunchFileError(f'{path}: Expected only one root')
        if 'launch' not in document:
            raise LaunchFileError(f"{path}: Expected 'launch' as root tag")
        return yaml_entity(document, path)
