"""Actions about events and the launch itself: log, emit, shut down, register handlers, call code."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.event import Event
from launch.event_handler import BaseEventHandler
from launch.events.process.process_exited import ProcessExited
from launch.events.shutdown import Shutdown as ShutdownEvent
from launch.frontend.expose import expose_action
from launch.launch_description_entity import LaunchDescriptionEntity
from launch.logging import get_logger
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext


@expose_action('log')
class LogInfo(Action):
    """`[INFO] [launch.user]: <msg>`."""

    def __init__(self, *, msg: SomeSubstitutionsType, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.msg = normalize_to_list_of_substitutions(msg)

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        return cls, {'msg': parser.substitutions(entity.get_attr('message'))}

    def execute(self, context: LaunchContext) -> None:
        get_logger('launch.user').info(perform_substitutions(context, self.msg))


class RegisterEventHandler(Action):
    def __init__(self, event_handler: BaseEventHandler, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        if not isinstance(event_handler, BaseEventHandler):
            raise TypeError(f"RegisterEventHandler expects an event handler, got '{type(event_handler)}'")
        self.event_handler = event_handler

    def execute(self, context: LaunchContext) -> None:
        context.register_event_handler(self.event_handler)


class UnregisterEventHandler(RegisterEventHandler):
    def execute(self, context: LaunchContext) -> None:
        context.unregister_event_handler(self.event_handler)


class EmitEvent(Action):
    def __init__(self, *, event: Event, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        if not isinstance(event, Event):
            raise TypeError(f"EmitEvent expects an event, got '{type(event)}'")
        self.event = event

    def execute(self, context: LaunchContext) -> None:
        context.emit_event_sync(self.event)


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


class OpaqueFunction(Action):
    """Call function(context, *args, **kwargs) at execution; visit the entities it returns."""

    def __init__(self, *, function: Callable[..., Iterable[LaunchDescriptionEntity] | None],
                 args: Iterable[Any] | None = None, kwargs: dict[str, Any] | None = None,
                 **action_kwargs: Any) -> None:
        super().__init__(**action_kwargs)
        if not callable(function):
            raise TypeError(f"OpaqueFunction expected a callable for 'function', got '{type(function)}'")
        self.function = function
        self.args = list(args or [])
        self.kwargs = dict(kwargs or {})

    def execute(self, context: LaunchContext) -> Iterable[LaunchDescriptionEntity] | None:
        return self.function(context, *self.args, **self.kwargs)
