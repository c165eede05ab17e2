"""SetRemap: every Node after it (in scope) gets `-r src:=dst`, before its own remappings."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.frontend.expose import expose_action
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext


@expose_action('set_remap')
class SetRemap(Action):
    """Every Node after this one (in scope) gets `-r src:=dst`, before its own remappings."""

    def __init__(self, src: SomeSubstitutionsType, dst: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.src = normalize_to_list_of_substitutions(src)
        self.dst = normalize_to_list_of_substitutions(dst)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """Read a <set_remap> tag's from and to attributes."""
        return cls, {'src': parser.substitutions(entity.get_attr('from')),
                     'dst': parser.substitutions(entity.get_attr('to'))}

    def execute(self, context: LaunchContext) -> None:
        """Add the rule to the remappings the scope's later Nodes get."""
        rule = (perform_substitutions(context, self.src), perform_substitutions(context, self.dst))
        context.launch_configurations['ros_remaps'] = [
            *context.launch_configurations.get('ros_remaps', []), rule]
