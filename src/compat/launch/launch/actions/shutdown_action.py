"""Shutdown (`<shutdown>`): shut the whole launch down."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from launch.actions.emit_event import EmitEvent
from launch.events.process.process_exited import ProcessExited
from launch.events.shutdown import Shutdown as ShutdownEvent
from launch.frontend.expose import expose_action
from launch.logging import get_logger
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext


@expose_action('shutdown')
class Shutdown(EmitEvent):
    """Shut the whole launch down (the ROS 1 `required="true"` when used as on_exit)."""

    def __init__(self, *, reason: SomeSubstitutionsType = 'reason not given', **kwargs: Any) -> None:
        self.reason = normalize_to_list_of_substitutions(reason)
        super().__init__(event=ShutdownEvent(), **kwargs)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        reason = entity.get_attr('reason', optional=True)
        return cls, {} if reason is None else {'reason': parser.substitutions(reason)}

    def execute(self, context: LaunchContext) -> None:
        try:
            event = context.locals.event
        except AttributeError:
            event = None
        if isinstance(event, ProcessExited):
            get_logger().info(f'process[{event.process_name}] was required: shutting down launched system')
        context.emit_event_sync(ShutdownEvent(reason=perform_substitutions(context, self.reason)))
