"""UnregisterEventHandler: remove an event handler from the launch."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.actions.register_event_handler import RegisterEventHandler

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class UnregisterEventHandler(RegisterEventHandler):
    def execute(self, context: LaunchContext) -> None:
        context.unregister_event_handler(self.event_handler)
