"""`ros2 param list`: the parameter names of one node, or of every node."""

import argparse
import re
from typing import Any

from ros2cli.api.node import node_names
from ros2cli.api.param import TYPE_NAMES, ParameterSession, _add_common, full_name
from ros2cli.node.strategy import NodeStrategy
from ros2cli.verb import VerbExtension


class ListVerb(VerbExtension):
    """Output a list of available parameters."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the common node options (node name optional) and --param-prefixes, --param-type, --filter."""
        _add_common(parser, node_required=False, timeout=False)
        parser.add_argument('--param-prefixes', nargs='+', default=[],
                            help='Only list parameters with the provided prefixes')
        parser.add_argument('--param-type', action='store_true',
                            help='Print parameter types with parameter names')
        parser.add_argument('--filter', metavar='REGEX', help='Only list parameters matching this regex')

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the parameter names of one node, or of every node that has parameter services, node by node.

        --filter is a regular expression matched at the start of each name; an invalid one gives the error
        message. Without a node name, a node whose services fail is reported in one line and the rest listed.
        """
        try:
            pattern = re.compile(args.filter) if args.filter else None
        except re.error as error:
            return f"Invalid --filter regex '{args.filter}': {error}"
        with NodeStrategy(args, spin_time=0.0 if args.node_name else None) as strategy:
            if args.node_name:
                targets = [full_name(args.node_name)]
            else:
                services = {name for name, _ in strategy.graph.service_names_and_types()}
                targets = [n for n in sorted(set(node_names(strategy.graph, args.include_hidden_nodes)))
                           if f'{n}/list_parameters' in services]
            for target in targets:
                self._list_node(args, strategy, target, pattern)
        return 0

    @staticmethod
    def _list_node(args: argparse.Namespace, strategy: Any, target: str, pattern: Any) -> None:
        try:
            with ParameterSession(args, target, 1.0 if args.node_name else 0.0, strategy) as session:
                names = [n for n in session.names(args.param_prefixes) if not pattern or pattern.match(n)]
                types = {}
                if args.param_type and names:
                    types = dict(zip(names, (v.type for v in session.values(names)), strict=True))
        except RuntimeError as error:
            if args.node_name:
                raise
            print(error)
            return
        if names and not args.node_name:
            print(f'{target}:')
        for name in names:
            print(f'  {name} (type: {TYPE_NAMES[types[name]]})' if args.param_type else f'  {name}')
