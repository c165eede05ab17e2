"""`ros2 daemon stop`: ask this domain's daemon to exit."""

import argparse

from ros2cli.verb import VerbExtension


class StopVerb(VerbExtension):
    """Stop the daemon if it is running."""

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Ask this domain's daemon to exit; an error message when its port is not free within 10 s."""
        # Lazy: `ros2 daemon -h` imports this module.
        from ros2cli.daemon.client import is_daemon_running, shutdown_daemon
        if not is_daemon_running():
            print('The daemon is not running')
            return 0
        if not shutdown_daemon():
            return 'Timed out waiting for daemon to shutdown'
        print('The daemon has been stopped')
        return 0
