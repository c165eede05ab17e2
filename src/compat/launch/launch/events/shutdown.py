"""Shutdown: the event that ends a launch."""

from launch.event import Event


class Shutdown(Event):
    """Ask the launch to shut down: processes are stopped, timers cancelled, then launch exits."""

    name = 'launch.events.Shutdown'

    def __init__(self, *, reason: str = 'reason not given', due_to_sigint: bool = False) -> None:
        self.reason = reason
        self.due_to_sigint = due_to_sigint
