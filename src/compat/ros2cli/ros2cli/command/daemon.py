"""`ros2 daemon start | stop | status`: the per-domain background process with the warm graph cache."""

import argparse

from ros2cli.command import VerbCommand
from ros2cli.verb import VerbExtension


class StartVerb(VerbExtension):
    """Start the daemon if it isn't running."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add -d/--debug, accepted as upstream's option; it changes nothing here."""
        parser.add_argument('-d', '--debug', action='store_true', help='Print debug messages')

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Start this domain's daemon unless one runs, and wait until it answers.

        An error message is returned when it does not answer within READY_TIMEOUT (10 s).
        """
        from ros2cli.daemon.client import is_daemon_running, spawn_daemon, wait_until
        if is_daemon_running() or not spawn_daemon():
            print('The daemon is already running')
            return 0
        if not wait_until(lambda: is_daemon_running(timeout=10.0)):
            return 'Timed out waiting for daemon to become ready'
        print('The daemon has been started')
        return 0


class StopVerb(VerbExtension):
    """Stop the daemon if it is running."""

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Ask this domain's daemon to exit; an error message when its port is not free within 10 s."""
        from ros2cli.daemon.client import is_daemon_running, shutdown_daemon
        if not is_daemon_running():
            print('The daemon is not running')
            return 0
        if not shutdown_daemon():
            return 'Timed out waiting for daemon to shutdown'
        print('The daemon has been stopped')
        return 0


class StatusVerb(VerbExtension):
    """Output the status of the daemon."""

    def main(self, *, args: argparse.Namespace) -> int:
        """Print whether this domain's daemon is running; the exit code is 0 either way."""
        from ros2cli.daemon.client import is_daemon_running
        print('The daemon is running' if is_daemon_running() else 'The daemon is not running')
        return 0


class DaemonCommand(VerbCommand):
    """Various daemon related sub-commands."""

    VERB_GROUP = 'ros2cli.daemon.verb'
