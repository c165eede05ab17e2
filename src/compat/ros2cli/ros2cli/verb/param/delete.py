"""`ros2 param delete`: unset one parameter."""

import argparse

from ros2cli.api.param import ParameterSession, _add_common, _set_one
from ros2cli.verb import VerbExtension


class DeleteVerb(VerbExtension):
    """Delete parameter."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the common node options and the parameter name."""
        _add_common(parser)
        parser.add_argument('parameter_name', help='Name of the parameter')

    def main(self, *, args: argparse.Namespace) -> int:
        """Delete the parameter (set it NOT_SET) and print the outcome; a refusal is explained on stderr."""
        # Lazy: the message packages import slowly, and `ros2 param -h` imports this module.
        from rcl_interfaces.msg import ParameterValue
        with ParameterSession(args, args.node_name) as session:
            _set_one(args, session, ParameterValue(type=0),
                     ('Deleted parameter successfully', 'Deleting parameter failed'))
        return 0
