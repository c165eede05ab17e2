"""DeclareLaunchArgument (`<arg>`): a launch argument and its default."""

from __future__ import annotations

from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.frontend.expose import expose_action
from launch.logging import get_logger
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitutions.text_substitution import TextSubstitution
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext


@expose_action('arg')
class DeclareLaunchArgument(Action):
    """A launch argument: given on the command line / by an include, else its default."""

    def __init__(self, name: str, *, default_value: SomeSubstitutionsType | None = None,
                 description: str | None = None, choices: Iterable[str] | None = None,
                 **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__name = name
        self.__default_value = (None if default_value is None
                                else normalize_to_list_of_substitutions(default_value))
        self.__choices = None if choices is None else list(choices)
        if self.__choices is not None:
            if not self.__choices:
                raise RuntimeError('Provided choices arg is empty')
            literal_default = self._literal_default()
            if literal_default is not None and literal_default not in self.__choices:
                raise RuntimeError(f"Provided default_value '{literal_default}' is not in provided "
                                   f'choices {self.__choices}')
        if description is None:
            description = ('no description given' if self.__choices is None
                           else f'One of: {self.__choices}')
        elif self.__choices is not None:
            if not description.endswith('.'):
                description += '.'
            description += f' Valid choices are: {self.__choices}'
        self.__description = description
        self._conditionally_included = False

    def _literal_default(self) -> str | None:
        if self.__default_value is None:
            return None
        if all(isinstance(sub, TextSubstitution) for sub in self.__default_value):
            return ''.join(sub.text for sub in self.__default_value)  # type: ignore[attr-defined]
        return None

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        kwargs: dict[str, Any] = {'name': entity.get_attr('name')}
        default = entity.get_attr('default', optional=True)
        if default is not None:
            kwargs['default_value'] = parser.substitutions(default)
        description = entity.get_attr('description', optional=True)
        if description is not None:
            kwargs['description'] = str(description)
        choices = entity.get_children('choice')
        if choices:
            kwargs['choices'] = [str(choice.get_attr('value')) for choice in choices]
            for choice in choices:
                choice.assert_entity_completely_parsed()
        return cls, kwargs

    @property
    def name(self) -> str:
        return self.__name

    @property
    def default_value(self) -> list | None:
        return self.__default_value

    @property
    def description(self) -> str:
        return self.__description

    @property
    def choices(self) -> list[str] | None:
        return self.__choices

    def describe(self) -> str:
        return f"DeclareLaunchArgument('{self.__name}')"

    def execute(self, context: LaunchContext) -> None:
        if self.__name not in context.launch_configurations:
            if self.__default_value is None:
                get_logger('launch.actions.declare_launch_argument').error(
                    f'Required launch argument "{self.__name}" (description: '
                    f'"{self.__description}") was not provided')
                raise RuntimeError(f'Required launch argument "{self.__name}" was not provided.')
            context.launch_configurations[self.__name] = perform_substitutions(
                context, self.__default_value)
        value = context.launch_configurations[self.__name]
        if self.__choices is not None and value not in self.__choices:
            raise RuntimeError(f'Argument "{self.__name}" provided value "{value}" is not valid. '
                               f'Valid options are: {self.__choices}')
