"""What the verbs of `ros2 action` share (upstream's ros2action.api): action lookups and arguments."""

import argparse

from ros2cli.completion import action_completer, with_completer
from ros2cli.graph_listing import types_of
from ros2cli.node.graph import Graph


def action_types(graph: Graph, action: str) -> list[str] | None:
    """The action's types in the graph, or None while the action is not (yet) in it."""
    return types_of(graph.action_names_and_types(), action)


def _action_argument(parser: argparse.ArgumentParser, help_text: str) -> None:
    with_completer(parser.add_argument('action_name', help=help_text), action_completer)
