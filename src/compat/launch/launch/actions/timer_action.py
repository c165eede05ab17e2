"""TimerAction: run actions once after a period, in the scope the timer was started in."""

from __future__ import annotations

import asyncio
import warnings
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.actions.pop_launch_configurations import PopLaunchConfigurations
from launch.actions.push_launch_configurations import PushLaunchConfigurations
from launch.event_handler import CallbackEventHandler
from launch.events.shutdown import Shutdown
from launch.events.timer_event import TimerEvent
from launch.frontend.expose import expose_action
from launch.launch_description_entity import LaunchDescriptionEntity
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities.type_utils import normalize_typed_substitution, perform_typed_substitution

if TYPE_CHECKING:
    from launch.event import Event
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext


@expose_action('timer')
class TimerAction(Action):
    """One-shot; keeps launch busy while pending; cancelled by shutdown unless told otherwise.

    The actions see the locals and launch configurations of the moment the timer started (as
    upstream launch does since ros2/launch#836), so a timer inside a group keeps its scope.
    """

    def __init__(self, *, period: float | SomeSubstitutionsType,
                 actions: Iterable[LaunchDescriptionEntity],
                 cancel_on_shutdown: bool | SomeSubstitutionsType = True, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        if isinstance(period, str):
            # Jazzy still takes the text of a number, with a warning; substitutions are the way
            warnings.warn('TimerAction: give period as a number (or substitutions), not as a string '
                          'literal; string literals are deprecated', stacklevel=2)
            try:
                period = float(period)
            except ValueError:
                raise ValueError(f"TimerAction period must be a number of seconds, got '{period}'") from None
        if isinstance(period, int) and not isinstance(period, bool):
            period = float(period)
        self.period = normalize_typed_substitution(period, float)
        self.actions = list(actions)
        self.cancel_on_shutdown = normalize_typed_substitution(cancel_on_shutdown, bool)
        self._future: asyncio.Future | None = None
        self._handle: asyncio.TimerHandle | None = None

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        kwargs: dict[str, Any] = {
            'period': parser.parse_if_substitutions(entity.get_attr('period', data_type=float))}
        cancel = entity.get_attr('cancel_on_shutdown', data_type=bool, optional=True)
        if cancel is not None:
            kwargs['cancel_on_shutdown'] = parser.parse_if_substitutions(cancel)
        kwargs['actions'] = parser.parse_actions(entity.action_children())
        return cls, kwargs

    def describe_conditional_sub_entities(self) -> list[tuple[str, Iterable[LaunchDescriptionEntity]]]:
        return [('after a timer', self.actions)]

    def get_asyncio_future(self) -> asyncio.Future | None:
        return self._future

    def cancel(self) -> None:
        if self._handle is not None:
            self._handle.cancel()
        if self._future is not None and not self._future.done():
            self._future.set_result(None)

    def execute(self, context: LaunchContext) -> None:
        try:
            period = perform_typed_substitution(context, self.period, float)
            cancel_on_shutdown = perform_typed_substitution(context, self.cancel_on_shutdown, bool)
        except ValueError as error:
            raise ValueError(f'TimerAction: {error}') from None
        captured_locals = context.get_locals_as_dict()
        captured_configurations = dict(context.launch_configurations)

        def on_timer(_event: Event, ctx: LaunchContext) -> list[LaunchDescriptionEntity]:
            ctx.extend_locals(captured_locals)
            return [PushLaunchConfigurations(), _ReplaceLaunchConfigurations(captured_configurations),
                    *self.actions, PopLaunchConfigurations()]

        context.register_event_handler(CallbackEventHandler(
            matcher=lambda event: isinstance(event, TimerEvent) and event.timer_action is self,
            callback=on_timer, handle_once=True))
        if cancel_on_shutdown:
            context.register_event_handler(CallbackEventHandler(
                matcher=lambda event: isinstance(event, Shutdown),
                callback=lambda _event, _ctx: self.cancel(), handle_once=True))
        loop = asyncio.get_running_loop()
        self._future = loop.create_future()

        def fire() -> None:
            if self._future is not None and not self._future.done():
                context.emit_event_sync(TimerEvent(timer_action=self, actions=self.actions))
                self._future.set_result(None)

        self._handle = loop.call_later(period, fire)


class _ReplaceLaunchConfigurations(Action):
    """Replace every launch configuration by the given ones (inside a pushed scope)."""

    def __init__(self, configurations: dict[str, Any], **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.configurations = configurations

    def execute(self, context: LaunchContext) -> None:
        context.launch_configurations.clear()
        context.launch_configurations.update(self.configurations)
