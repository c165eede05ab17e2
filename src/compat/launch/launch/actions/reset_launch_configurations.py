"""ResetLaunchConfigurations (`<reset>`): forget every launch configuration, keeping only the given ones."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.frontend.expose import expose_action
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext


@expose_action('reset')
class ResetLaunchConfigurations(Action):
    """Clear the launch configurations of the current scope, then set launch_configurations.

    The kept values are performed before the clearing, so `{'robot': LaunchConfiguration('robot')}`
    carries a value through.  In a launch file: `<reset><keep name="robot" value="$(var robot)"/></reset>`.
    """

    def __init__(self,
                 launch_configurations: dict[SomeSubstitutionsType, SomeSubstitutionsType] | None = None,
                 **kwargs: Any) -> None:
        super().__init__(**kwargs)
        if launch_configurations is not None and not isinstance(launch_configurations, dict):
            raise TypeError("ResetLaunchConfigurations expects a dict of launch configurations to keep, "
                            f"got '{type(launch_configurations).__name__}'")
        self.launch_configurations = [
            (normalize_to_list_of_substitutions(name), normalize_to_list_of_substitutions(value))
            for name, value in (launch_configurations or {}).items()]

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        kept = {}
        for item in entity.get_children('keep'):
            kept[tuple(parser.substitutions(item.get_attr('name')))] = parser.substitutions(
                item.get_attr('value'))
            item.assert_entity_completely_parsed()
        return cls, {'launch_configurations': kept} if kept else {}

    def execute(self, context: LaunchContext) -> None:
        kept = {perform_substitutions(context, name): perform_substitutions(context, value)
                for name, value in self.launch_configurations}
        context.launch_configurations.clear()
        context.launch_configurations.update(kept)
