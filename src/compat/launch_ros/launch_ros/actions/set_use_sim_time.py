"""SetUseSimTime: every Node after it (in scope) gets use_sim_time."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from launch.frontend.expose import expose_action
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

from launch_ros.actions.set_parameter import SetParameter

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext


@expose_action('set_use_sim_time')
class SetUseSimTime(SetParameter):
    """SetParameter('use_sim_time', value) where value must be 'true' or 'false' (any case)."""

    def __init__(self, value: SomeSubstitutionsType | bool, **kwargs: Any) -> None:
        text = str(value).lower() if isinstance(value, bool) else value
        super().__init__('use_sim_time', normalize_to_list_of_substitutions(text), **kwargs)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """Read a <set_use_sim_time> tag's value attribute."""
        return cls, {'value': parser.substitutions(entity.get_attr('value'))}

    def execute(self, context: LaunchContext) -> None:
        """Check the value and add use_sim_time to the scope's parameters; ValueError unless true/false."""
        text = perform_substitutions(context, self.value).strip().lower()
        if text not in ('true', 'false'):
            raise ValueError(f"SetUseSimTime value must be 'true' or 'false', got {text!r}")
        self.value = text == 'true'
        super().execute(context)
