"""XML and YAML launch files: tags become actions, `$(...)` values become substitutions."""

from __future__ import annotations

import importlib
import importlib.util
import os
import tempfile
from typing import TYPE_CHECKING, TextIO, overload

from launch.frontend import substitution_parser, type_utils
from launch.frontend.entity import Entity, LaunchFileError, load_xml_root, load_yaml_root
from launch.frontend.expose import action_parse_methods, expose_action, expose_substitution
from launch.substitution import Substitution
from launch.substitutions.text_substitution import TextSubstitution

if TYPE_CHECKING:
    from launch.action import Action
    from launch.condition import Condition
    from launch.launch_description import LaunchDescription

__all__ = [
    'Entity', 'LaunchFileError', 'Parser', 'expose_action', 'expose_substitution',
    'load_launch_file', 'parse_substitution', 'type_utils',
]

# Packages whose actions and substitutions extend the frontend, loaded when present.
EXTENSION_MODULES = ('launch_ros.actions', 'launch_ros.substitutions')


_extensions_loaded = False


def _load_extensions() -> None:
    """Register the tags and `$(...)` names of launch and of the installed extensions, once."""
    global _extensions_loaded
    if _extensions_loaded:
        return
    import launch.actions
    import launch.frontend.builtin_substitutions  # noqa: F401

    for module in EXTENSION_MODULES:
        if importlib.util.find_spec(module.split('.')[0]) is not None:
            importlib.import_module(module)
    _extensions_loaded = True


def parse_substitution(text: str) -> list[Substitution]:
    """The substitutions of one `$(...)` template ('' gives one empty text)."""
    _load_extensions()
    return substitution_parser.parse_substitution(text)


# The file extensions the frontend reads, and which root loader reads each.
FRONTEND_EXTENSIONS = {'xml': 'xml', 'yaml': 'yaml', 'yml': 'yaml'}


class Parser:
    """Turns entities into actions; parse methods of actions call back into it."""

    @classmethod
    def get_available_extensions(cls) -> list[str]:
        """The extensions of the launch files the frontend reads."""
        return list(FRONTEND_EXTENSIONS)

    @classmethod
    def is_extension_valid(cls, extension: str) -> bool:
        return extension.lstrip('.') in FRONTEND_EXTENSIONS

    @classmethod
    def get_file_extension_from_filename(cls, filename: str | os.PathLike) -> str:
        return os.path.splitext(os.fspath(filename))[1].lstrip('.')

    @classmethod
    def is_filename_valid(cls, filename: str | os.PathLike) -> bool:
        return cls.is_extension_valid(cls.get_file_extension_from_filename(filename))

    @classmethod
    def load(cls, file: str | os.PathLike | TextIO) -> tuple[Entity, Parser]:
        """The root entity of an XML or YAML launch file and a parser for it.

        As upstream's `root, parser = Parser.load(path)` then `parser.parse_description(root)`.
        file is a path or an open text file; the extension picks the format, and a file with
        another extension is tried as XML, then as YAML.
        """
        _load_extensions()
        if isinstance(file, (str, os.PathLike)):
            return cls._load_path(os.fspath(file)), cls()
        name = getattr(file, 'name', None)
        if isinstance(name, str) and os.path.isfile(name):
            return cls._load_path(name), cls()
        # A stream with no file behind it (io.StringIO): its text, in a file of its own.
        extension = cls.get_file_extension_from_filename(name) if isinstance(name, str) else ''
        with tempfile.TemporaryDirectory() as directory:
            path = os.path.join(directory, 'launch' + (f'.{extension}' if extension else ''))
            with open(path, 'w', encoding='utf-8') as handle:
                handle.write(file.read())
            return cls._load_path(path), cls()

    @classmethod
    def _load_path(cls, path: str) -> Entity:
        if not os.path.isfile(path):
            raise LaunchFileError(f"launch file '{path}' does not exist")
        chosen = FRONTEND_EXTENSIONS.get(cls.get_file_extension_from_filename(path))
        formats = [chosen] if chosen else ['xml', 'yaml']
        errors = []
        for format_name in formats:
            try:
                return load_xml_root(path) if format_name == 'xml' else load_yaml_root(path)
            except LaunchFileError as error:
                errors.append(str(error))
        raise LaunchFileError('; '.join(errors))

    def parse_substitution(self, text: str) -> list[Substitution]:
        return substitution_parser.parse_substitution(text)

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
            return substitution_parser.parse_substitution(value)
        raise TypeError(f'expected a text value, got {value!r}')

    def boolean(self, entity: Entity, name: str) -> bool | None:
        """A true/false attribute, read with YAML's rules as upstream's typed attributes are.

        true/false, yes/no, on/off in any case (YAML booleans pass as they are).
        """
        from launch.utilities.type_utils import coerce_to_type

        value = entity.get_attr(name, optional=True)
        if value is None or isinstance(value, bool):
            return value
        try:
            return coerce_to_type(str(value).strip(), bool)
        except ValueError:
            raise entity.error(f"attribute '{name}' of `{entity.type_name}` must be true or false "
                               f'(or yes/no, on/off), got {value!r}') from None

    def parse_condition(self, entity: Entity) -> Condition | None:
        from launch.conditions.if_condition import IfCondition
        from launch.conditions.unless_condition import UnlessCondition

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
        cls = action_parse_methods.get(entity.type_name)
        if cls is None:
            raise entity.error(f'Unrecognized entity of the type: {entity.type_name}')
        try:
            action_class, kwargs = cls.parse(entity, self)
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
        from launch.launch_description import LaunchDescription

        deprecated = root.get_attr('deprecated', optional=True)
        actions = self.parse_actions(root.action_children())
        root.assert_entity_completely_parsed()
        return LaunchDescription(actions, deprecated_reason=deprecated)


def load_launch_file(path: str, format_name: str) -> LaunchDescription:
    """Read an XML ('xml') or YAML ('yaml') launch file into a LaunchDescription."""
    _load_extensions()
    root = load_xml_root(path) if format_name == 'xml' else load_yaml_root(path)
    return Parser().parse_description(root)
