"""Parser: the frontend's reading of XML and YAML launch files into launch descriptions.

The formats are the implementations found through the entry point group 'launch.frontend.parser'
(launch_xml's `xml`, launch_yaml's `yaml`): each reads its files into entities, and this class
turns entities into actions through the tags the actions expose.
"""

from __future__ import annotations

import os
import tempfile
import warnings
from typing import TYPE_CHECKING, Any, TextIO, overload

from launch.conditions.if_condition import IfCondition
from launch.conditions.unless_condition import UnlessCondition
from launch.frontend.entity import Entity, LaunchFileError
from launch.frontend.expose import action_parse_methods, get_entry_points, load_launch_extensions
from launch.frontend.parse_substitution import parse_if_substitutions, parse_substitution
from launch.invalid_launch_file_error import InvalidLaunchFileError
from launch.launch_description import LaunchDescription
from launch.substitutions.text_substitution import TextSubstitution
from launch.utilities.type_utils import coerce_to_type

if TYPE_CHECKING:
    from launch.action import Action
    from launch.condition import Condition
    from launch.substitution import Substitution

# Format name -> parser class of that format, sorted by name, once loaded.
_implementations: dict[str, type[Parser]] | None = None


class InvalidFrontendLaunchFileError(InvalidLaunchFileError):
    """An XML or YAML launch file could not be read (an InvalidLaunchFileError, as upstream)."""


class Parser:
    """Turns entities into actions; parse methods of actions call back into it.

    Parser.load(file) picks the format's parser by the file's extension; an implementation's own
    load reads its format only.
    """

    @classmethod
    def load_launch_extensions(cls) -> None:
        """Import the launch extensions (entry point group 'launch.frontend.launch_extension'), once."""
        load_launch_extensions()

    @classmethod
    def load_parser_implementations(cls) -> dict[str, type[Parser]]:
        """The format parsers (entry point group 'launch.frontend.parser'): name -> class, by name."""
        global _implementations
        if _implementations is None:
            found = {entry_point.name: entry_point.load()
                     for entry_point in get_entry_points('launch.frontend.parser')}
            _implementations = dict(sorted(found.items()))
        return _implementations

    @classmethod
    def get_file_extensions(cls) -> set[str]:
        """The file extensions of this format (an implementation's); none for the frontend itself."""
        return set()

    @classmethod
    def get_available_extensions(cls) -> list[str]:
        """The extensions of the launch files the frontend reads."""
        return [extension for implementation in cls.load_parser_implementations().values()
                for extension in sorted(implementation.get_file_extensions())]

    @classmethod
    def is_extension_valid(cls, extension: str) -> bool:
        """Deprecated in Jazzy (use is_filename_valid)."""
        warnings.warn('Parser.is_extension_valid is deprecated: use Parser.is_filename_valid', stacklevel=2)
        return cls._knows_extension(extension)

    @classmethod
    def get_parser_from_extension(cls, extension: str) -> type[Parser] | None:
        """Deprecated in Jazzy (use get_parsers_from_filename)."""
        warnings.warn('Parser.get_parser_from_extension is deprecated: use Parser.get_parsers_from_filename',
                      stacklevel=2)
        return cls._parser_for_extension(extension)

    @classmethod
    def get_parsers_from_filename(cls, filename: str | os.PathLike) -> list[type[Parser]]:
        """The installed format parsers that read files of this name (by its extension)."""
        return [implementation for implementation in cls.load_parser_implementations().values()
                if implementation.may_parse(filename)]

    @classmethod
    def may_parse(cls, filename: str | os.PathLike) -> bool:
        """Whether this format reads a file of this name (by its extension)."""
        return cls.get_file_extension_from_filename(filename) in cls.get_file_extensions()

    @classmethod
    def _knows_extension(cls, extension: str) -> bool:
        return extension.lstrip('.') in cls.get_available_extensions()

    @classmethod
    def _parser_for_extension(cls, extension: str) -> type[Parser] | None:
        """The parser of the format whose files have this extension, if one is installed."""
        for implementation in cls.load_parser_implementations().values():
            if extension.lstrip('.') in implementation.get_file_extensions():
                return implementation
        return None

    @classmethod
    def get_file_extension_from_filename(cls, filename: str | os.PathLike) -> str:
        return os.path.splitext(os.fspath(filename))[1].lstrip('.')

    @classmethod
    def is_filename_valid(cls, filename: str | os.PathLike) -> bool:
        return cls._knows_extension(cls.get_file_extension_from_filename(filename))

    @classmethod
    def load(cls, file: str | os.PathLike | TextIO) -> tuple[Entity, Parser]:
        """The root entity of an XML or YAML launch file and a parser for it.

        As upstream's `root, parser = Parser.load(path)` then `parser.parse_description(root)`.
        file is a path or an open text file; the extension picks the format, and a file with
        another extension is tried as XML, then as YAML.
        """
        cls.load_launch_extensions()
        if isinstance(file, (str, os.PathLike)):
            return cls._load_path(os.fspath(file))
        name = getattr(file, 'name', None)
        if isinstance(name, str) and os.path.isfile(name):
            return cls._load_path(name)
        # A stream with no file behind it (io.StringIO): its text, in a file of its own.
        extension = cls.get_file_extension_from_filename(name) if isinstance(name, str) else ''
        with tempfile.TemporaryDirectory() as directory:
            path = os.path.join(directory, 'launch' + (f'.{extension}' if extension else ''))
            with open(path, 'w', encoding='utf-8') as handle:
                handle.write(file.read())
            return cls._load_path(path)

    @classmethod
    def _load_path(cls, path: str) -> tuple[Entity, Parser]:
        if not os.path.isfile(path):
            raise LaunchFileError(f"launch file '{path}' does not exist")
        implementations: list[type[Parser]]
        if cls.get_file_extensions():  # an implementation reads its own format
            implementations = [cls]
        else:
            chosen = cls._parser_for_extension(cls.get_file_extension_from_filename(path))
            implementations = [chosen] if chosen else list(cls.load_parser_implementations().values())
        if not implementations:
            raise LaunchFileError(f"launch file '{path}': no frontend parser is installed (entry point "
                                  "group 'launch.frontend.parser')")
        errors = []
        for implementation in implementations:
            try:
                return implementation._load_root(path), implementation()
            except LaunchFileError as error:
                errors.append(str(error))
        raise LaunchFileError('; '.join(errors))

    @classmethod
    def _load_root(cls, path: str) -> Entity:
        """The root entity of a file of this format (implementations read their format here)."""
        raise NotImplementedError(cls.__name__)

    def parse_substitution(self, text: str) -> list[Substitution]:
        return parse_substitution(text)

    def parse_if_substitutions(self, value: Any) -> Any:
        """A typed attribute's value, its text parsed for `$(...)` (see parse_substitution's module)."""
        return parse_if_substitutions(value)

    @overload
    def substitutions(self, value: None) -> None: ...

    @overload
    def substitutions(self, value: str | float) -> list[Substitution]: ...

    def substitutions(self, value: object) -> list[Substitution] | None:
        """An attribute value as substitutions (YAML scalars become their text); None stays None."""
        if value is None:
            return None
        if isinstance(value, bool):
            return [TextSubstitution(text=str(value).lower())]
        if isinstance(value, (int, float)):
            return [TextSubstitution(text=str(value))]
        if isinstance(value, str):
            return parse_substitution(value)
        raise TypeError(f'expected a text value, got {value!r}')

    def boolean(self, entity: Entity, name: str) -> bool | None:
        """A true/false attribute, read with YAML's rules as upstream's typed attributes are.

        true/false, yes/no, on/off in any case (YAML booleans pass as they are).
        """
        value = entity.get_attr(name, optional=True)
        if value is None or isinstance(value, bool):
            return value
        try:
            return coerce_to_type(str(value).strip(), bool)
        except ValueError:
            raise entity.error(f"attribute '{name}' of `{entity.type_name}` must be true or false "
                               f'(or yes/no, on/off), got {value!r}') from None

    def parse_condition(self, entity: Entity) -> Condition | None:
        if_value = entity.get_attr('if', optional=True)
        unless_value = entity.get_attr('unless', optional=True)
        if if_value is not None and unless_value is not None:
            raise entity.error("'if' and 'unless' cannot be used at the same time")
        if if_value is not None:
            return IfCondition(self.substitutions(if_value))
        if unless_value is not None:
            return UnlessCondition(self.substitutions(unless_value))
        return None

    def parse_action(self, entity: Entity) -> Action:
        parse = action_parse_methods.get(entity.type_name)
        if parse is None:
            raise entity.error(f'Unrecognized entity of the type: {entity.type_name}')
        try:
            action_class, kwargs = parse(entity, self)
            condition = self.parse_condition(entity)
            if condition is not None:
                kwargs['condition'] = condition
            entity.assert_entity_completely_parsed()
            return action_class(**kwargs)
        except LaunchFileError:
            raise
        except (ValueError, TypeError, KeyError, RuntimeError) as error:
            raise entity.error(f'{type(error).__name__}: {error}') from None

    def parse_actions(self, entities: list[Entity]) -> list[Action]:
        return [self.parse_action(entity) for entity in entities]

    def parse_description(self, root: Entity) -> LaunchDescription:
        deprecated = root.get_attr('deprecated', optional=True)
        actions = self.parse_actions(root.action_children())
        root.assert_entity_completely_parsed()
        return LaunchDescription(actions, deprecated_reason=deprecated)


def load_launch_file(path: str, format_name: str) -> LaunchDescription:
    """Read an XML ('xml') or YAML ('yaml') launch file into a LaunchDescription."""
    Parser.load_launch_extensions()
    implementation = (Parser.load_parser_implementations().get(format_name)
                      or Parser._parser_for_extension(format_name))
    if implementation is None:
        raise LaunchFileError(f"launch file '{path}': no frontend parser for the format '{format_name}'")
    return implementation().parse_description(implementation._load_root(path))
