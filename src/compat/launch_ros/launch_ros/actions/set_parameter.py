"""SetParameter: every Node after it (in scope) gets `-p name:=value`."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.frontend.expose import expose_action
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

from launch_ros.parameter_descriptions import evaluate_value

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext


@expose_action('set_parameter')
class SetParameter(Action):
    """Every Node after this one (in scope) gets `-p name:=value`."""

    def __init__(self, name: SomeSubstitutionsType, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.name = normalize_to_list_of_substitutions(name)
        self.value = value

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """Read a <set_parameter> tag's name and value (a non-text YAML value passes as it is)."""
        value = entity.get_attr('value')
        return cls, {'name': parser.substitutions(entity.get_attr('name')),
                     'value': parser.substitutions(value) if isinstance(value, str) else value}

    def execute(self, context: LaunchContext) -> None:
        """Add name:=value to the parameters the scope's later Nodes get."""
        name = perform_substitutions(context, self.name)
        value = evaluate_value(context, self.value, name)
        # A new list, not an append: the enclosing scope keeps its own.
        context.launch_configurations['global_params'] = [
            *context.launch_configurations.get('global_params', []), (name, value)]
