"""Parser of XML launch files (the `xml` entry of the group 'launch.frontend.parser')."""

from __future__ import annotations

from xml.parsers import expat

from launch.frontend.entity import LaunchFileError
from launch.frontend.parser import Parser as BaseParser

from launch_xml.entity import Entity


class Parser(BaseParser):
    """Reads `.xml` launch files."""

    @classmethod
    def get_file_extensions(cls) -> set[str]:
        """The file extensions of XML launch files."""
        return {'xml'}

    @classmethod
    def _load_root(cls, path: str) -> Entity:
        """Parse with expat directly, which knows the line of every element."""
        parser = expat.ParserCreate()
        stack: list[Entity] = []
        roots: list[Entity] = []

        def start(tag: str, attributes: dict[str, str]) -> None:
            entity = Entity(tag, attributes, [], path, parser.CurrentLineNumber)
            if stack:
                entity.parent = stack[-1]
            (stack[-1]._elements if stack else roots).append(entity)
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
