"""`ros2 doctor` and its alias `ros2 wtf`: run the checks, print the reports, or run a verb (hello)."""

from __future__ import annotations

import argparse

from ros2cli.command import CommandExtension, add_subparsers_on_demand


class DoctorCommand(CommandExtension):
    """Check ROS setup and other potential issues."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """--report/-r or --report-failed/-rf, --exclude-packages/-ep, --include-warnings/-iw; the verbs."""
        which = parser.add_mutually_exclusive_group()
        which.add_argument('--report', '-r', action='store_true', help='Print all reports.')
        which.add_argument('--report-failed', '-rf', action='store_true',
                           help='Print reports of failed checks only.')
        parser.add_argument('--exclude-packages', '-ep', action='store_true',
                            help='Exclude package checks or report.')
        parser.add_argument('--include-warnings', '-iw', action='store_true',
                            help='Include warnings as failed checks. Warnings are ignored by default.')
        # Optional: without a verb the command runs the checks (or prints the reports), as before.
        add_subparsers_on_demand(parser, cli_name, '_verb', 'ros2doctor.verb', required=False)

    def main(self, *, parser: argparse.ArgumentParser, args: argparse.Namespace) -> int | str | None:
        """Run the verb given; without one, print every report (-r) or run the checks (then -rf's reports).

        The checks say how many failed, and the exit code is 0 either way, as upstream's: the findings are
        in the output.
        """
        if hasattr(args, '_verb'):
            return args._verb.main(args=args)
        # Lazy: the checks import rclpy, and `ros2 -h` imports this module.
        from ros2doctor.api import generate_reports, run_checks
        from ros2doctor.api.format import format_print

        if args.report:
            for report in generate_reports(exclude_packages=args.exclude_packages):
                format_print(report)
            return 0
        failed, fail, total = run_checks(include_warnings=args.include_warnings,
                                         exclude_packages=args.exclude_packages)
        if fail:
            print(f'\n{fail}/{total} check(s) failed\n')
            print('Failed modules:', *sorted(failed))
        else:
            print(f'\nAll {total} checks passed\n')
        if args.report_failed and fail:
            for report in generate_reports(categories=failed, exclude_packages=args.exclude_packages):
                format_print(report)
        return 0


class WtfCommand(DoctorCommand):
    """Use `wtf` as alias to `doctor`."""
