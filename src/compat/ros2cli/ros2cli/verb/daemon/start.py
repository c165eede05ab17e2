"""`ros2 daemon start`: start this domain's daemon unless one runs."""

import argparse

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
        # Lazy: `ros2 daemon -h` imports this module.
        from ros2cli.daemon.client import is_daemon_running, spawn_daemon, wait_until
        if is_daemon_running() or not spawn_daemon():
            print('The daemon is already running')
            return 0
        if not wait_until(lambda: is_daemon_running(timeout=10.0)):
            return 'Timed out waiting for daemon to become ready'
        print('The daemon has been started')
        return 0
