"""`ros2 param describe`: declared parameters' types, descriptions and constraints."""

import argparse
import sys

from ros2cli.api.param import TYPE_NAMES, ParameterSession, _add_common
from ros2cli.verb import VerbExtension


class DescribeVerb(VerbExtension):
    """Show descriptive information about declared parameters."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the common node options and one or more parameter names."""
        _add_common(parser)
        parser.add_argument('parameter_names', nargs='+', help='Names of the parameters')

    def main(self, *, args: argparse.Namespace) -> int:
        """Print each declared parameter's type, description and constraints.

        Names the node has not declared are reported afterwards on stderr, with a 'did you mean' hint; the
        exit code is 0 all the same.
        """
        with ParameterSession(args, args.node_name) as session:
            # One request per name: a node answers nothing at all when any name is undeclared.
            descriptors, hints = [], {}
            for name in args.parameter_names:
                found = session.describe(name)
                descriptors += found
                if not found:
                    hints[name] = session.unknown(name)
        for descriptor in descriptors:
            print(f'Parameter name: {descriptor.name}')
            print(f'  Type: {TYPE_NAMES.get(descriptor.type, descriptor.type)}')
            if descriptor.description:
                print(f'  Description: {descriptor.description}')
            print('  Constraints:')
            if descriptor.read_only:
                print('    Read only: true')
            ranges = list(descriptor.floating_point_range) or list(descriptor.integer_range)
            if ranges:
                print(f'    Min value: {ranges[0].from_value}')
                print(f'    Max value: {ranges[0].to_value}')
                if ranges[0].step != 0:
                    print(f'    Step: {ranges[0].step}')
            if descriptor.additional_constraints:
                print(f'    Additional constraints: {descriptor.additional_constraints}')
        for name, hint in hints.items():
            print(f"Parameter '{name}' is not declared by node '{session.node_name}'{hint}", file=sys.stderr)
        return 0
