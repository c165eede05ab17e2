"""StateTransition: a lifecycle node announced a transition on its transition_event topic."""

from __future__ import annotations

from typing import Any

from launch.event import Event


class StateTransition(Event):
    """A TransitionEvent message that a LifecycleNode action's node published.

    transition, start_state and goal_state are the labels of the message: a configure is announced
    twice, start 'unconfigured' -> goal 'configuring', then start 'configuring' -> goal 'inactive'
    once the node's on_configure succeeded.
    """

    name = 'launch_ros.events.lifecycle.StateTransition'

    def __init__(self, *, action: Any, msg: Any) -> None:
        self.action = action
        self.msg = msg
        self.timestamp = msg.timestamp
        self.transition = msg.transition.label
        self.start_state = msg.start_state.label
        self.goal_state = msg.goal_state.label
