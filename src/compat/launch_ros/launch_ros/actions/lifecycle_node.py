"""LifecycleNode: a Node whose lifecycle launch watches and drives (ChangeState events)."""

from __future__ import annotations

import asyncio
import threading
import time
from collections.abc import Callable
from typing import TYPE_CHECKING, Any

import lifecycle_msgs.msg
import lifecycle_msgs.srv
from launch.action import Action
from launch.actions import EmitEvent
from launch.event_handler import BaseEventHandler
from launch.frontend.expose import expose_action
from launch.logging import get_logger

from launch_ros.actions.node import Node
from launch_ros.events.lifecycle import ChangeState, StateTransition
from launch_ros.events.matchers import matches_node_name
from launch_ros.ros_adapters import get_ros_node

if TYPE_CHECKING:
    from launch.event import Event
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext
    from launch.some_entities_type import SomeEntitiesType

# Seconds between checks for shutdown while waiting for the change_state service or its answer.
SERVICE_POLL = 0.5
# The node says each transition once on <node>/transition_event, which keeps no history: before a
# change, launch waits (at most EVENT_MATCH_TIMEOUT s) until its subscription has matched the node's
# publisher, then EVENT_MATCH_SETTLE s more for the publisher's side of the match, or the event of
# that change is lost and OnStateTransition never fires (the node's service can be found first).
EVENT_MATCH_TIMEOUT = 5.0
EVENT_MATCH_SETTLE = 0.2


class _CallbackEventHandler(BaseEventHandler):
    """Calls callback(event, context) for each matching event; what it returns is visited next."""

    def __init__(self, *, matcher: Callable[[Event], bool],
                 callback: Callable[[Event, LaunchContext], SomeEntitiesType | None]) -> None:
        super().__init__(matcher=matcher)
        self.__callback = callback

    def handle(self, event: Event, context: LaunchContext) -> SomeEntitiesType | None:
        """Record the event in context.locals as every handler does, then call the callback."""
        super().handle(event, context)
        return self.__callback(event, context)


@expose_action('lifecycle_node')
class LifecycleNode(Node):
    """A lifecycle node (rclpy.lifecycle / rclcpp_lifecycle); name is required.

    Launch subscribes to <node>/transition_event and emits a StateTransition event for each
    message; a ChangeState event whose matcher accepts this action makes launch call
    <node>/change_state.  With autostart=True launch configures and then activates the node.
    Upstream requires namespace too; here a missing one counts as '' (the pushed namespace, or the root one),
    so that the node's full name, and with it its services, is known.
    """

    def __init__(self, *, name: Any = None, namespace: Any = None, autostart: bool = False,
                 **kwargs: Any) -> None:
        if name is None:
            raise TypeError("LifecycleNode requires 'name': launch finds the node's lifecycle services by it")
        super().__init__(name=name, namespace='' if namespace is None else namespace, **kwargs)
        self.__autostart = autostart
        self.__client: Any = None
        self.__subscription: Any = None
        self.__logger = get_logger('launch_ros.actions.lifecycle_node')

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        """Read a <lifecycle_node> tag: a <node>'s arguments, plus the optional boolean autostart."""
        _cls, kwargs = super().parse(entity, parser)
        autostart = parser.boolean(entity, 'autostart')
        if autostart is not None:
            kwargs['autostart'] = autostart
        return cls, kwargs

    @property
    def is_lifecycle_node(self) -> bool:
        """Always True: the mark OnStateTransition checks its target_lifecycle_node for."""
        return True

    @property
    def node_autostart(self) -> bool:
        """Whether launch configures and then activates the node itself (the autostart argument)."""
        return self.__autostart

    def describe(self) -> str:
        """'LifecycleNode(package=..., executable=...)'."""
        return 'Lifecycle' + super().describe()

    def _on_transition_message(self, context: LaunchContext, msg: Any) -> None:
        """In the adapter's thread: hand the event to launch's loop."""
        event = StateTransition(action=self, msg=msg)
        loop = context.asyncio_loop
        if loop is not None and not loop.is_closed():
            loop.call_soon_threadsafe(context.emit_event_sync, event)

    def _call_change_state(self, context: LaunchContext, transition_id: int) -> None:
        """In a worker thread: call change_state, giving up when launch shuts down."""
        label = ChangeState.valid_transitions[transition_id]
        while not self.__client.wait_for_service(timeout_sec=SERVICE_POLL):
            if context.is_shutdown:
                self.__logger.warning(f"Abandoning wait for the '{self.__client.srv_name}' service, "
                                      'due to shutdown.')
                return
        matched_by = time.monotonic() + EVENT_MATCH_TIMEOUT
        if self.__subscription.get_publisher_count() == 0:
            while self.__subscription.get_publisher_count() == 0 and time.monotonic() < matched_by:
                if context.is_shutdown:
                    return
                time.sleep(0.02)
            time.sleep(EVENT_MATCH_SETTLE)
        request = lifecycle_msgs.srv.ChangeState.Request()
        request.transition.id = transition_id
        answered = threading.Event()
        future = self.__client.call_async(request)
        future.add_done_callback(lambda _future: answered.set())
        while not answered.wait(SERVICE_POLL):
            if context.is_shutdown:
                self.__logger.warning(f"Abandoning wait for the '{self.__client.srv_name}' service "
                                      'response, due to shutdown.')
                future.cancel()
                return
        if future.exception() is not None:
            raise future.exception()
        if not future.result().success:
            self.__logger.error(f"Failed to make transition '{label}' for LifecycleNode '{self.node_name}'")

    def _on_change_state(self, event: Event, context: LaunchContext) -> None:
        assert isinstance(event, ChangeState)
        if not event.lifecycle_node_matcher(self):
            return
        loop = asyncio.get_running_loop()
        context.add_completion_future(
            loop.run_in_executor(None, self._call_change_state, context, event.transition_id))

    def _autostart(self, event: Event, context: LaunchContext) -> list[Action]:
        assert isinstance(event, StateTransition)
        if event.start_state == 'configuring' and event.goal_state == 'inactive':
            return [EmitEvent(event=ChangeState(lifecycle_node_matcher=matches_node_name(self.node_name),
                                                transition_id=lifecycle_msgs.msg.Transition.TRANSITION_ACTIVATE))]
        return []

    def execute(self, context: LaunchContext) -> None:
        """Start the node as a Node does, then watch its transitions and drive its change_state service.

        With autostart, request the configure transition at once (the activate one follows it).
        Raises RuntimeError if the node's full name could not be worked out.
        """
        super().execute(context)  # expands the name, starts the process
        if not self.is_node_name_fully_specified():
            raise RuntimeError(f'lifecycle node name could not be expanded: {self.node_name}')
        ros_node = get_ros_node(context)
        self.__subscription = ros_node.create_subscription(
            lifecycle_msgs.msg.TransitionEvent, f'{self.node_name}/transition_event',
            lambda msg: self._on_transition_message(context, msg), 10)
        self.__client = ros_node.create_client(lifecycle_msgs.srv.ChangeState,
                                               f'{self.node_name}/change_state')
        context.register_event_handler(_CallbackEventHandler(
            matcher=lambda event: isinstance(event, ChangeState), callback=self._on_change_state))
        if self.__autostart:
            context.register_event_handler(_CallbackEventHandler(
                matcher=lambda event: isinstance(event, StateTransition) and event.action is self,
                callback=self._autostart))
            self._on_change_state(ChangeState(lifecycle_node_matcher=lambda action: action is self,
                                              transition_id=lifecycle_msgs.msg.Transition.TRANSITION_CONFIGURE),
                                  context)
