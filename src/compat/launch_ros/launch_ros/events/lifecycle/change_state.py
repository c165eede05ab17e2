"""ChangeState: ask matching lifecycle nodes to make a transition."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import lifecycle_msgs.msg
from launch.event import Event

# id -> label of every transition and every state, from lifecycle_msgs' constants.
_TRANSITION = lifecycle_msgs.msg.Transition
_STATE = lifecycle_msgs.msg.State
VALID_TRANSITIONS = {
    _TRANSITION.TRANSITION_CREATE: 'TRANSITION_CREATE',
    _TRANSITION.TRANSITION_CONFIGURE: 'TRANSITION_CONFIGURE',
    _TRANSITION.TRANSITION_CLEANUP: 'TRANSITION_CLEANUP',
    _TRANSITION.TRANSITION_ACTIVATE: 'TRANSITION_ACTIVATE',
    _TRANSITION.TRANSITION_DEACTIVATE: 'TRANSITION_DEACTIVATE',
    _TRANSITION.TRANSITION_UNCONFIGURED_SHUTDOWN: 'TRANSITION_UNCONFIGURED_SHUTDOWN',
    _TRANSITION.TRANSITION_INACTIVE_SHUTDOWN: 'TRANSITION_INACTIVE_SHUTDOWN',
    _TRANSITION.TRANSITION_ACTIVE_SHUTDOWN: 'TRANSITION_ACTIVE_SHUTDOWN',
    _TRANSITION.TRANSITION_DESTROY: 'TRANSITION_DESTROY',
}
VALID_STATES = {
    _STATE.PRIMARY_STATE_UNKNOWN: 'PRIMARY_STATE_UNKNOWN',
    _STATE.PRIMARY_STATE_UNCONFIGURED: 'PRIMARY_STATE_UNCONFIGURED',
    _STATE.PRIMARY_STATE_INACTIVE: 'PRIMARY_STATE_INACTIVE',
    _STATE.PRIMARY_STATE_ACTIVE: 'PRIMARY_STATE_ACTIVE',
    _STATE.PRIMARY_STATE_FINALIZED: 'PRIMARY_STATE_FINALIZED',
    _STATE.TRANSITION_STATE_CONFIGURING: 'TRANSITION_STATE_CONFIGURING',
    _STATE.TRANSITION_STATE_CLEANINGUP: 'TRANSITION_STATE_CLEANINGUP',
    _STATE.TRANSITION_STATE_SHUTTINGDOWN: 'TRANSITION_STATE_SHUTTINGDOWN',
    _STATE.TRANSITION_STATE_ACTIVATING: 'TRANSITION_STATE_ACTIVATING',
    _STATE.TRANSITION_STATE_DEACTIVATING: 'TRANSITION_STATE_DEACTIVATING',
    _STATE.TRANSITION_STATE_ERRORPROCESSING: 'TRANSITION_STATE_ERRORPROCESSING',
}


class ChangeState(Event):
    """A request that the matching lifecycle nodes make a transition.

    Every LifecycleNode action for which lifecycle_node_matcher(action) is true calls its node's
    change_state service with transition_id (a lifecycle_msgs Transition constant).
    """

    name = 'launch_ros.events.lifecycle.ChangeState'
    valid_transitions = VALID_TRANSITIONS
    valid_states = VALID_STATES

    def __init__(self, *, lifecycle_node_matcher: Callable[[Any], bool], transition_id: int) -> None:
        if not callable(lifecycle_node_matcher):
            raise TypeError("ChangeState expects a callable 'lifecycle_node_matcher', got "
                            f"'{type(lifecycle_node_matcher).__name__}'")
        if isinstance(transition_id, bool) or transition_id not in VALID_TRANSITIONS:
            raise ValueError(f"unknown lifecycle transition id {transition_id!r}, expected one of "
                             f'{sorted(VALID_TRANSITIONS)} (lifecycle_msgs.msg.Transition)')
        self.lifecycle_node_matcher = lifecycle_node_matcher
        self.transition_id = transition_id
