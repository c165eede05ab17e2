"""`ros2 param set`: set one parameter to a value given as YAML."""

import argparse

from ros2cli.api.param import ParameterSession, _add_common, _set_one
from ros2cli.verb import VerbExtension


class SetVerb(VerbExtension):
    """Set parameter."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the common node options, the parameter name and its value (YAML: '3' is an integer)."""
        _add_common(parser)
        parser.add_argument('parameter_name', help='Name of the parameter')
        parser.add_argument('value', help='Value of the parameter')

    def main(self, *, args: argparse.Namespace) -> int:
        """Set the parameter and print the outcome; a refusal goes to stderr (exit code 0, as upstream)."""
        # Lazy: rclpy is slow to import, and `ros2 param -h` imports this module.
        from rclpy.parameter import get_parameter_value
        with ParameterSession(args, args.node_name) as session:
            _set_one(args, session, get_parameter_value(args.value),
                     ('Set parameter successful', 'Setting parameter failed'))
        return 0
