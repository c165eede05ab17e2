"""owl demo (make demo): the course's robot (chapter 4) live on real ROS 2 for about 20 seconds.

Starts the simulated Owl Kit (IMU, pan and tilt servos, camera), the course's projects on it
(imu_control_robot points the head where the IMU points, display_camera shows the camera,
imu_turtle drives turtlesim's turtle with the IMU) and robot_view (the kit live in a browser, with
its plots and the camera), prints the front door's address (one address for every page) and a few
readable lines of what happens, then stops everything with Ctrl-C's signal, as a user at a terminal
would.

With --project tracking it is section 4.6's robot instead: a red ball swings to and fro in front of
the robot and track_object keeps it in the middle of the camera's picture; each line says how far off
it is.
"""

from __future__ import annotations

import argparse
import sys

from owl_cli.command import Command

PROJECTS = ('imu', 'tracking')


class DemoCommand(Command):
    """`owl demo [--seconds N] [--project imu|tracking]`."""

    help = "the course's chapter 4 robot live on the simulated kit for about 20 s (make demo)"
    description = sys.modules[__name__].__doc__  # the module's (in here __doc__ is the class's)
    formatter_class = argparse.RawDescriptionHelpFormatter

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """--seconds, --report-every, --project."""
        parser.add_argument('--seconds', type=float, default=20.0, help='how long to run (default 20)')
        parser.add_argument('--report-every', type=float, default=4.0, metavar='SECONDS',
                            help='seconds between two status lines (default 4)')
        parser.add_argument('--project', choices=PROJECTS, default='imu',
                            help="the chapter 4 robot to run: 'imu' (4.4-4.5, the IMU steers) or 'tracking' "
                                 '(4.6, the camera follows a red ball)')

    def main(self, *, parser: argparse.ArgumentParser, args: argparse.Namespace) -> int:
        """Run the demo; the exit code: 130 after Ctrl-C, 1 if it cannot start."""
        if not args.seconds > 0 or not args.report_every > 0:
            parser.error('--seconds and --report-every must be positive numbers')
        # Imported here: OpenCV and the ROS messages load for the demo, not for every owl command.
        from owl_cli.demo.robot import run_demo

        try:
            return run_demo(args.seconds, args.report_every, args.project)
        except KeyboardInterrupt:
            print('== interrupted; every node was stopped', file=sys.stderr)
            return 130
        except (AssertionError, FileNotFoundError) as error:  # a node did not come up, or is not built
            print(f'== demo failed to start: {error}', file=sys.stderr)
            return 1
