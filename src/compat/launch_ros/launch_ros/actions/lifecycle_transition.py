"""LifecycleTransition: make lifecycle nodes go through a list of transitions, one after the other."""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import TYPE_CHECKING, Any, ClassVar

import lifecycle_msgs.msg
from launch.action import Action
from launch.actions import EmitEvent, OpaqueFunction, RegisterEventHandler
from launch.event_handler import BaseEventHandler, EventHandler
from launch.logging import get_logger
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.utilities import normalize_to_list_of_substitutions, perform_substitutions

from launch_ros.events.lifecycle import ChangeState, StateTransition
from launch_ros.events.matchers import matches_node_name

if TYPE_CHECKING:
    from launch.event import Event
    from launch.launch_context import LaunchContext

_TRANSITION = lifecycle_msgs.msg.Transition


class LifecycleTransition(Action):
    """Request transition_ids of every named node, in order, each once the previous one succeeded.

    The first transition is requested at once; each node's next one when the node has reached the
    goal state of the previous one.  A node that ends up in 'errorprocessing' gets no further
    transitions.  The sequence must be possible.
    """

    # transition id -> the StateTransition (start, goal) labels that mean it succeeded
    transition_targets: ClassVar[dict[int, dict[str, str]]] = {
        _TRANSITION.TRANSITION_CONFIGURE: {'start_state': 'configuring', 'goal_state': 'inactive'},
        _TRANSITION.TRANSITION_CLEANUP: {'start_state': 'cleaningup', 'goal_state': 'unconfigured'},
        _TRANSITION.TRANSITION_ACTIVATE: {'start_state': 'activating', 'goal_state': 'active'},
        _TRANSITION.TRANSITION_DEACTIVATE: {'start_state': 'deactivating', 'goal_state': 'inactive'},
        _TRANSITION.TRANSITION_UNCONFIGURED_SHUTDOWN: {'start_state': 'shuttingdown',
                                                       'goal_state': 'finalized'},
        _TRANSITION.TRANSITION_INACTIVE_SHUTDOWN: {'start_state': 'shuttingdown', 'goal_state': 'finalized'},
        _TRANSITION.TRANSITION_ACTIVE_SHUTDOWN: {'start_state': 'shuttingdown', 'goal_state': 'finalized'},
    }

    def __init__(self, *, lifecycle_node_names: Iterable[SomeSubstitutionsType],
                 transition_ids: Iterable[int | SomeSubstitutionsType], **kwargs: Any) -> None:
        super().__init__(**kwargs)
        if isinstance(lifecycle_node_names, str) or isinstance(transition_ids, (str, int)):
            raise TypeError('LifecycleTransition expects lists: lifecycle_node_names=[...], '
                            'transition_ids=[...]')
        names = list(lifecycle_node_names)
        ids = list(transition_ids)
        if not names:
            raise ValueError('No lifecycle_node_names provided.')
        if not ids:
            raise ValueError('No transition_ids provided.')
        self.lifecycle_node_names = [normalize_to_list_of_substitutions(name) for name in names]
        self.transition_ids = [normalize_to_list_of_substitutions(str(i) if isinstance(i, int) else i)
                               for i in ids]
        self.__handlers: dict[str, list[BaseEventHandler]] = {}

    def _stop(self, context: LaunchContext, node_name: str, reason: str | None = None) -> None:
        if reason is not None:
            get_logger('launch_ros.actions.lifecycle_transition').info(
                f"Stopping transitions for {node_name} because '{reason}'")
        for handler in self.__handlers.get(node_name, []):
            try:
                context.unregister_event_handler(handler)
            except ValueError:  # already handled once
                pass

    def execute(self, context: LaunchContext) -> list[Action]:
        """Register the handlers that chain each node's transitions, then request the first ones.

        Raises ValueError for a transition id that is not an integer or has no known goal state.
        """
        names = [perform_substitutions(context, name) for name in self.lifecycle_node_names]
        ids = []
        for item in self.transition_ids:
            text = perform_substitutions(context, item)
            try:
                ids.append(int(text))
            except ValueError:
                raise ValueError(f'expected an integer lifecycle transition id, got {text!r}') from None
            if ids[-1] not in self.transition_targets:
                raise ValueError(f'lifecycle transition id {ids[-1]} cannot be waited for, expected one of '
                                 f'{sorted(self.transition_targets)}')
        first_requests: list[Action] = []
        registrations: list[Action] = []
        for name in names:
            full_name = name if name.startswith('/') else '/' + name
            requests = [EmitEvent(event=ChangeState(lifecycle_node_matcher=matches_node_name(full_name),
                                                    transition_id=i)) for i in ids]
            handlers: list[BaseEventHandler] = []
            for index, transition_id in enumerate(ids):
                target = self.transition_targets[transition_id]
                finish = OpaqueFunction(function=lambda ctx, n=full_name: self._stop(ctx, n))
                then: list[Any] = [requests[index + 1]] if index + 1 < len(ids) else [finish]
                matcher = match_node_name_start_goal(full_name, target['start_state'], target['goal_state'])
                handlers.append(EventHandler(matcher=matcher, entities=then, handle_once=True))
            error_handler = EventHandler(
                matcher=match_node_name_goal(full_name, 'errorprocessing'),
                entities=[OpaqueFunction(function=lambda ctx, n=full_name: self._stop(
                    ctx, n, 'error occurred during transitions'))],
                handle_once=True)
            handlers.append(error_handler)
            self.__handlers[full_name] = handlers
            context.register_event_handler(error_handler)
            registrations += [RegisterEventHandler(handler) for handler in handlers[:-1]]
            first_requests.append(requests[0])
        return [*registrations, *first_requests]


def match_node_name_start_goal(node_name: str, start_state: str, goal_state: str) -> Callable[[Event], bool]:
    """Matcher of the StateTransition of node node_name ('/' added if missing) from start to goal state."""
    goal_matcher = match_node_name_goal(node_name, goal_state)
    return lambda event: (goal_matcher(event) and isinstance(event, StateTransition)
                          and event.start_state == start_state)


def match_node_name_goal(node_name: str, goal_state: str) -> Callable[[Event], bool]:
    """Matcher of a StateTransition of node node_name ('/' added if missing) into goal_state."""
    full_name = node_name if node_name.startswith('/') else '/' + node_name
    return lambda event: (isinstance(event, StateTransition) and event.action.node_name == full_name
                          and event.goal_state == goal_state)
