"""XML and YAML launch files: tags become actions, `$(...)` values become substitutions."""

from __future__ import annotations

import importlib
import importlib.util
from typing import TYPE_CHECKING, Any

from launch.frontend import substitution_parser
from launch.frontend.entity import Entity, LaunchFileError, load_xml_root, load_yaml_root
from launch.frontend.expose import action_parse_methods, expose_action, expose_substitution
from launch.substitution import Substitution, TextSubstitution

if TYPE_CHECKING:
    from launch.action import Action
    from launch.condition import Condition
    from launch.launch_description import LaunchDescription

__all__ = [
    'Entity', 'LaunchFileError', 'Parser', 'expose_action', 'expose_substitution',
    'load_launch_file', 'parse_substitution',
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


class Parser:
    """Turns entities into actions; parse methods of actions call back into it."""

    def parse_substitution(self, text: str) -> list[Substitution]:
        return substitution_parser.parse_substitution(text)

    def substitutions(self, value: Any) -> list[Substitution] | None:
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
        """A true/false attribute: YAML booleans, or 'true'/'false'/'1'/'0' text."""
        value = entity.get_attr(name, optional=True)
        if value is None or isinstance(value, bool):
            return value
        text = str(value).strip().lower()
        if text in ('true', '1'):
            return True
        if text in ('false', '0'):
            return False
        raise entity.error(f"attribute '{name}' of `{entity.type_name}` must be true or false, "
                           f'got {value!r}')

    def parse_condition(self, entity: Entity) -> Condition | None:
        from launch.conditions import IfCondition, UnlessCondition

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
