"""ShutdownProcess: stop some processes."""

from launch.events.process.process_targeted_event import ProcessTargetedEvent


class ShutdownProcess(ProcessTargetedEvent):
    """Stop the matching processes (SIGINT, then the SIGTERM/SIGKILL escalation)."""
