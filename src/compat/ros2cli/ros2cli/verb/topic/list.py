"""`ros2 topic list`: the topics in the graph, with their types or counts."""

import argparse

from ros2cli.api.topic import _add_hidden_argument, _include_hidden, visible_topics
from ros2cli.graph_listing import print_listing
from ros2cli.node.strategy import NodeStrategy, add_strategy_arguments
from ros2cli.verb import VerbExtension


class ListVerb(VerbExtension):
    """Output a list of available topics."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the listing options (-t, -c, -v, --include-hidden-topics) and the NodeStrategy options."""
        add_strategy_arguments(parser)
        parser.add_argument('-t', '--show-types', action='store_true',
                            help='Additionally show the topic type')
        parser.add_argument('-c', '--count-topics', action='store_true',
                            help='Only display the number of topics discovered')
        _add_hidden_argument(parser)
        parser.add_argument('-v', '--verbose', action='store_true',
                            help='List full details about each topic')

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the topic names (with their types for -t, or only how many there are for -c).

        -v lists published and subscribed topics instead, each with its number of publishers or
        subscribers.
        """
        with NodeStrategy(args) as strategy:
            topics = visible_topics(strategy.graph, _include_hidden(args))
            if args.count_topics:
                print(len(topics))
                return 0
            if args.verbose:
                graph = strategy.graph
                counts = {name: (graph.count_publishers(name), graph.count_subscribers(name))
                          for name, _ in topics}
        if args.verbose:
            for title, index, word in (('Published topics:', 0, 'publisher'),
                                       ('Subscribed topics:', 1, 'subscriber')):
                print(title)
                for name, types in topics:
                    count = counts[name][index]
                    if count:
                        print(f" * {name} [{', '.join(types)}] {count} {word}{'s' if count > 1 else ''}")
                print()
            return 0
        return print_listing(topics, args.show_types, count_only=False)
