"""Set and unset one entry of a string dictionary of the launch context.

Environment variables and launch configurations are both name -> text maps on the context; their
Set/Unset actions differ only in which map they change (`entries`).
"""

from __future__ import annotations

from collections.abc import MutableMapping
from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext


class NamedValueAction(Action):
    """Base of actions on entries(context)[name]; subclasses say which map entries() is."""

    def __init__(self, name: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.name = normalize_to_list_of_substitutions(name)

    @staticmethod
    def entries(context: LaunchContext) -> MutableMapping[str, str]:
        raise NotImplementedError


class SetNamedValue(NamedValueAction):
    """Base of actions that set entries(context)[name] = value."""

    def __init__(self, name: SomeSubstitutionsType, value: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(name, **kwargs)
        self.value = normalize_to_list_of_substitutions(value)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        return cls, {'name': parser.substitutions(entity.get_attr('name')),
                     'value': parser.substitutions(entity.get_attr('value'))}

    def execute(self, context: LaunchContext) -> None:
        self.entries(context)[perform_substitutions(context, self.name)] = (
            perform_substitutions(context, self.value))


class UnsetNamedValue(NamedValueAction):
    """Base of actions that remove entries(context)[name], if present."""

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        return cls, {'name': parser.substitutions(entity.get_attr('name'))}

    def execute(self, context: LaunchContext) -> None:
        self.entries(context).pop(perform_substitutions(context, self.name), None)
