"""AppendEnvironmentVariable (`<append_env>`): add a value to a path-like variable."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.frontend.expose import expose_action
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions
from launch.utilities.type_utils import perform_typed_substitution

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext


@expose_action('append_env')
class AppendEnvironmentVariable(Action):
    """Append (or prepend) a value to a separator-joined variable such as a path list."""

    def __init__(self, name: SomeSubstitutionsType, value: SomeSubstitutionsType, *,
                 prepend: bool | SomeSubstitutionsType = False,
                 separator: SomeSubstitutionsType = os.pathsep, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.name = normalize_to_list_of_substitutions(name)
        self.value = normalize_to_list_of_substitutions(value)
        self.prepend = prepend if isinstance(prepend, bool) else normalize_to_list_of_substitutions(prepend)
        self.separator = normalize_to_list_of_substitutions(separator)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        kwargs: dict[str, Any] = {'name': parser.substitutions(entity.get_attr('name')),
                                  'value': parser.substitutions(entity.get_attr('value'))}
        for key in ('prepend', 'separator'):
            value = entity.get_attr(key, optional=True)
            if value is not None:
                kwargs[key] = parser.substitutions(value)
        return cls, kwargs

    def execute(self, context: LaunchContext) -> None:
        name = perform_substitutions(context, self.name)
        value = perform_substitutions(context, self.value)
        separator = perform_substitutions(context, self.separator)
        prepend = (self.prepend if isinstance(self.prepend, bool)
                   else perform_typed_substitution(context, self.prepend, bool))
        current = context.environment.get(name)
        if not current:
            context.environment[name] = value
        else:
            context.environment[name] = (value + separator + current if prepend
                                         else current + separator + value)
