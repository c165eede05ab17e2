"""OnStateTransition: react to lifecycle transitions of one or every LifecycleNode."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from launch.event import Event
from launch.event_handler import EventHandler

from launch_ros.events.lifecycle import StateTransition


class OnStateTransition(EventHandler):
    """Matches StateTransition events; each given criterion (None: any) must hold.

    target_lifecycle_node must be a LifecycleNode action; transition, start_state and goal_state
    compare with the labels the node published.  A custom matcher replaces all of them.
    """

    def __init__(self, *, entities: Any, target_lifecycle_node: Any = None,
                 transition: str | None = None, start_state: str | None = None,
                 goal_state: str | None = None, matcher: Callable[[Event], bool] | None = None,
                 **kwargs: Any) -> None:
        if target_lifecycle_node is not None and not getattr(target_lifecycle_node, 'is_lifecycle_node',
                                                             False):
            raise TypeError('OnStateTransition requires a LifecycleNode action as target_lifecycle_node, '
                            f"got '{type(target_lifecycle_node).__name__}'")
        if matcher is None:
            def matcher(event: Event) -> bool:
                return (isinstance(event, StateTransition)
                        and (target_lifecycle_node is None or event.action is target_lifecycle_node)
                        and (transition is None or event.transition == transition)
                        and (start_state is None or event.start_state == start_state)
                        and (goal_state is None or event.goal_state == goal_state))
        super().__init__(matcher=matcher, entities=entities, **kwargs)
        self.target_lifecycle_node = target_lifecycle_node
