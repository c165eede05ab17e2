"""`ros2 topic find`: the topics of a given type."""

import argparse

from ros2cli.api.topic import _add_hidden_argument, _include_hidden, _type_argument, visible_topics
from ros2cli.graph_listing import print_names_of_type
from ros2cli.node.strategy import NodeStrategy, add_strategy_arguments
from ros2cli.verb import VerbExtension


class FindVerb(VerbExtension):
    """Output a list of available topics of a given type."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the message type, -c/--count-topics, --include-hidden-topics and the NodeStrategy options."""
        _type_argument(parser, help_text='Name of the ROS topic type to filter for '
                       "(e.g. 'std_msgs/msg/String')")
        add_strategy_arguments(parser)
        parser.add_argument('-c', '--count-topics', action='store_true',
                            help='Only display the number of topics discovered')
        _add_hidden_argument(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the names of the topics of that type (or only how many there are for -c)."""
        with NodeStrategy(args) as strategy:
            topics = visible_topics(strategy.graph, _include_hidden(args))
        return print_names_of_type(topics, args.message_type, args.count_topics)
