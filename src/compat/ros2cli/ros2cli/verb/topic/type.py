"""`ros2 topic type`: a topic's types."""

import argparse

from ros2cli.api.topic import _add_hidden_argument, _include_hidden, _topic_argument, visible_topics
from ros2cli.graph_listing import print_types
from ros2cli.node.strategy import NodeStrategy, add_strategy_arguments
from ros2cli.verb import VerbExtension


class TypeVerb(VerbExtension):
    """Print a topic's type."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the topic name, --include-hidden-topics and the NodeStrategy options."""
        _topic_argument(parser, 'Name of the ROS topic to get type (e.g. \'/chatter\')')
        _add_hidden_argument(parser)
        add_strategy_arguments(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the topic's types one a line; exit code 1 when the topic never shows up (or is hidden)."""
        with NodeStrategy(args) as strategy:
            return print_types(strategy, lambda graph: visible_topics(graph, _include_hidden(args)),
                               args.topic_name)
