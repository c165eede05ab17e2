"""`ros2 daemon status`: whether this domain's daemon is running."""

import argparse

from ros2cli.verb import VerbExtension


class StatusVerb(VerbExtension):
    """Output the status of the daemon."""

    def main(self, *, args: argparse.Namespace) -> int:
        """Print whether this domain's daemon is running; the exit code is 0 either way."""
        # Lazy: `ros2 daemon -h` imports this module.
        from ros2cli.daemon.client import is_daemon_running
        print('The daemon is running' if is_daemon_running() else 'The daemon is not running')
        return 0
