"""`ros2 param get`: one parameter's value."""

import argparse

from ros2cli.api.param import VALUE_LABELS, ParameterSession, _add_common, value_text
from ros2cli.verb import VerbExtension


class GetVerb(VerbExtension):
    """Get parameter."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the common node options, the parameter name and --hide-type."""
        _add_common(parser)
        parser.add_argument('parameter_name', help='Name of the parameter')
        parser.add_argument('--hide-type', action='store_true', help='Hide the type information')

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the value after its type's label ('Integer value is: 3'), or the value alone for --hide-type.

        An undeclared parameter gives the error message, with a 'did you mean' hint.
        """
        with ParameterSession(args, args.node_name) as session:
            values = session.values([args.parameter_name])
            if not values:
                return (f"Parameter not set: node '{session.node_name}' has no parameter "
                        f"'{args.parameter_name}'{session.unknown(args.parameter_name)}")
        value = values[0]
        if value.type == 0:
            print('Parameter not set.')
            return 0
        if value.type not in VALUE_LABELS:
            return f"Unknown parameter type '{value.type}'"
        text = value_text(value)
        print(text if args.hide_type else f'{VALUE_LABELS[value.type]} {text}')
        return 0
