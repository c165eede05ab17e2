"""`ros2 action list | info | type | send_goal` (Jazzy has no `action find`; Rolling added it)."""

import argparse
import sys
from typing import Any

from ros2cli.command import VerbCommand
from ros2cli.node.graph import Graph
from ros2cli.verb import VerbExtension

STATUS_NAMES = {0: 'UNKNOWN', 1: 'ACCEPTED', 2: 'EXECUTING', 3: 'CANCELING', 4: 'SUCCEEDED', 5: 'CANCELED',
                6: 'ABORTED'}


def action_types(graph: Graph, action: str) -> list[str] | None:
    """The action's types in the graph, or None while the action is not (yet) in it."""
    from ros2cli.graph_listing import types_of
    return types_of(graph.action_names_and_types(), action)


def _action_argument(parser: argparse.ArgumentParser, help_text: str) -> None:
    from ros2cli.completion import action_completer, with_completer
    with_completer(parser.add_argument('action_name', help=help_text), action_completer)


class ListVerb(VerbExtension):
    """Output a list of action names."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add -t/--show-types, -c/--count-actions and the NodeStrategy options."""
        from ros2cli.node.strategy import add_strategy_arguments
        parser.add_argument('-t', '--show-types', action='store_true',
                            help='Additionally show the action type')
        parser.add_argument('-c', '--count-actions', action='store_true',
                            help='Only display the number of actions discovered')
        add_strategy_arguments(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the action names (with their types for -t, or only how many there are for -c)."""
        from ros2cli.graph_listing import print_listing
        from ros2cli.node.strategy import NodeStrategy
        with NodeStrategy(args) as strategy:
            actions = strategy.graph.action_names_and_types()
        return print_listing(actions, args.show_types, args.count_actions)


class InfoVerb(VerbExtension):
    """Print information about an action."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the action name, -t/--show-types, -c/--count and the NodeStrategy options."""
        from ros2cli.node.strategy import add_strategy_arguments
        _action_argument(parser, "Name of the ROS action to get info (e.g. '/fibonacci')")
        parser.add_argument('-t', '--show-types', action='store_true',
                            help='Additionally show the action type')
        parser.add_argument('-c', '--count', action='store_true', help='Only display the number of action '
                            'clients and action servers')
        add_strategy_arguments(parser)

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the nodes that are the action's clients and servers (with types for -t, only counts for -c).

        The name must be absolute, else its error message is returned. An action that is not in the
        graph (after the discovery grace) gives empty sections and, when a known name is close, a
        'did you mean' line on stderr.
        """
        from owl_common.graph import full_node_name
        from owl_common.hints import did_you_mean

        from ros2cli.node.strategy import NodeStrategy

        if not args.action_name.startswith('/') or args.action_name.endswith('/') or '//' in args.action_name:
            return f"Invalid action name '{args.action_name}': it must be absolute, e.g. '/fibonacci'"
        with NodeStrategy(args) as strategy:
            graph = strategy.graph
            strategy.wait_until(lambda: action_types(graph, args.action_name) is not None)
            # (node's full name, the action's types) for each client and server of the action
            clients: list[tuple[str, list[str]]] = []
            servers: list[tuple[str, list[str]]] = []
            for name, namespace in graph.node_names_and_namespaces():
                node = full_node_name(namespace, name)
                for found, query in ((clients, graph.action_clients_by_node),
                                     (servers, graph.action_servers_by_node)):
                    for action, types in query(name, namespace):
                        if action == args.action_name:
                            found.append((node, types))
            known = [name for name, _ in graph.action_names_and_types()]
        print(f'Action: {args.action_name}')
        for title, entries in (('Action clients', clients), ('Action servers', servers)):
            print(f'{title}: {len(entries)}')
            if not args.count:
                for node, types in sorted(entries):
                    print(f"    {node} [{', '.join(types)}]" if args.show_types else f'    {node}')
        if not clients and not servers:
            hint = did_you_mean(args.action_name, known)
            if hint:
                print(f"No action '{args.action_name}' in the graph{hint}", file=sys.stderr)
        return 0


class TypeVerb(VerbExtension):
    """Print a action's type."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the action name and the NodeStrategy options."""
        from ros2cli.node.strategy import add_strategy_arguments
        _action_argument(parser, "Name of the ROS action to get type (e.g. '/fibonacci')")
        add_strategy_arguments(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print the action's types one a line; exit code 1 when the action never shows up."""
        from ros2cli.graph_listing import print_types
        from ros2cli.node.strategy import NodeStrategy
        with NodeStrategy(args) as strategy:
            return print_types(strategy, lambda graph: graph.action_names_and_types(), args.action_name)


def indented_yaml(message: Any, first_line_indent: str) -> str:
    """Upstream's shape: the indent before the first YAML line only."""
    from rosidl_runtime_py.convert import message_to_yaml
    return first_line_indent + message_to_yaml(message)


class SendGoalVerb(VerbExtension):
    """Send an action goal."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the action name and type, the goal's YAML values (or --stdin) and -f/--feedback."""
        from ros2cli.api.topic import add_values_arguments
        from ros2cli.completion import action_type_completer, with_completer
        _action_argument(parser, "Name of the ROS action (e.g. '/fibonacci')")
        with_completer(parser.add_argument('action_type', help="Type of the ROS action (e.g. "
                                           "'example_interfaces/action/Fibonacci')"), action_type_completer)
        add_values_arguments(parser, 'goal', 'order: 5')
        parser.add_argument('-f', '--feedback', action='store_true',
                            help='Echo feedback messages for the goal')

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Send one goal made of the YAML values, print its feedback (-f) and result, and return 0.

        An invalid action type or goal field is returned as the error message. Ctrl-C cancels a goal that
        is running and exits with 2.
        """
        from rosidl_runtime_py.set_message import FieldError, set_message_fields
        from rosidl_runtime_py.utilities import InvalidType, canonical_type, import_type

        from ros2cli.api.topic import read_values

        try:
            action_class = import_type(args.action_type, 'action')
        except InvalidType as error:
            return f'The passed action type is invalid: {error}'
        values = read_values(args, 'message fields')
        try:
            goal = action_class.Goal()
            set_message_fields(goal, values)
        except FieldError as error:
            return f'Failed to populate message fields: {error}'
        node_name = '_ros2cli_send_goal_' + canonical_type(args.action_type, 'action').replace('/', '_')
        return self._send(args, action_class, goal, node_name)

    def _send(self, args: argparse.Namespace, action_class: Any, goal: Any, node_name: str) -> int | str:
        import rclpy
        from owl_common.graph import expand_topic_name
        from rclpy.action import ActionClient, get_action_names_and_types
        from rclpy.node import Node
        from rosidl_runtime_py.convert import message_to_yaml

        from ros2cli.names import WaitingHint
        from ros2cli.node.direct import NAMED_LOOKUP_GRACE, tear_down

        rclpy.init(args=[])
        node = Node(node_name, start_parameter_services=False)
        action_name = expand_topic_name(args.action_name)
        client = ActionClient(node, action_class, action_name)
        goal_handle = None
        try:
            print('Waiting for an action server to become available...')
            hint = WaitingHint(f"action server for '{action_name}'", action_name, NAMED_LOOKUP_GRACE)
            while not client.wait_for_server(timeout_sec=0.5):
                hint.update(lambda: [name for name, _ in get_action_names_and_types(node)])
            print(f'Sending goal:\n{indented_yaml(goal, "     ")}')

            # Feedback can be taken before the goal response (separate DDS topics); hold it until
            # "Goal accepted" is printed so the output keeps the order of events.
            held_feedback: list[str] = []
            goal_answered = False

            def on_feedback(feedback: Any) -> None:
                text = f'Feedback:\n    {message_to_yaml(feedback.feedback)}'
                if goal_answered:
                    print(text)
                else:
                    held_feedback.append(text)

            future = client.send_goal_async(goal, feedback_callback=on_feedback if args.feedback else None)
            rclpy.spin_until_future_complete(node, future)
            if future.exception() is not None:
                return f'Exception while sending goal: {future.exception()!r}'
            goal_handle = future.result()
            if not goal_handle.accepted:
                print('Goal was rejected.')
                return 0
            print(f'Goal accepted with ID: {bytes(goal_handle.goal_id.uuid).hex()}\n')
            goal_answered = True
            for text in held_feedback:
                print(text)
            result_future = goal_handle.get_result_async()
            rclpy.spin_until_future_complete(node, result_future)
            if result_future.exception() is not None:
                return f'Exception while getting result: {result_future.exception()!r}'
            response = result_future.result()
            goal_handle = None
            print(f'Result:\n    {message_to_yaml(response.result)}')
            print(f'Goal finished with status: {STATUS_NAMES.get(response.status, "UNKNOWN")}')
            return 0
        except KeyboardInterrupt:
            if goal_handle is not None:
                print('Canceling goal...')
                cancel = goal_handle.cancel_goal_async()
                rclpy.spin_until_future_complete(node, cancel, timeout_sec=5.0)
                if not cancel.done() or not cancel.result().goals_canceling:
                    return 'Failed to cancel goal'
                print('Goal canceled.')
            return 2
        finally:
            tear_down(node, client)


class ActionCommand(VerbCommand):
    """Various action related sub-commands."""

    VERB_GROUP = 'ros2action.verb'
