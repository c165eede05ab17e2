"""What the verbs of `ros2 service` share (upstream's ros2service.api): service lookups and arguments."""

import argparse
from typing import Any

from owl_common.graph import is_hidden_name

from ros2cli.completion import service_completer, with_completer
from ros2cli.node.graph import Graph


def _include_hidden(args: argparse.Namespace) -> bool:
    return bool(getattr(args, 'include_hidden_services', False)
                or getattr(args, 'command_include_hidden', False))


def _add_hidden_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument('--include-hidden-services', action='store_true',
                        help='Consider hidden services as well')


def visible_services(graph: Graph, include_hidden: bool) -> list[list[Any]]:
    """The graph's [name, [type, ...]] service entries, hidden services left out unless include_hidden."""
    return [[name, types] for name, types in graph.service_names_and_types()
            if include_hidden or not is_hidden_name(name)]


def _service_argument(parser: argparse.ArgumentParser, help_text: str) -> None:
    with_completer(parser.add_argument('service_name', help=help_text), service_completer)
