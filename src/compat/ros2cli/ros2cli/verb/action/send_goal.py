"""`ros2 action send_goal`: send one goal given as YAML, print its feedback and result."""

import argparse
from typing import Any

from owl_common.graph import expand_topic_name

from ros2cli.api.action import _action_argument
from ros2cli.api.topic import add_values_arguments, read_values
from ros2cli.completion import action_type_completer, with_completer
from ros2cli.names import WaitingHint
from ros2cli.node.direct import NAMED_LOOKUP_GRACE, tear_down
from ros2cli.verb import VerbExtension

STATUS_NAMES = {0: 'UNKNOWN', 1: 'ACCEPTED', 2: 'EXECUTING', 3: 'CANCELING', 4: 'SUCCEEDED', 5: 'CANCELED',
                6: 'ABORTED'}


def indented_yaml(message: Any, first_line_indent: str) -> str:
    """Upstream's shape: the indent before the first YAML line only."""
    # Lazy: rosidl_runtime_py imports yaml and rosidl_parser, and `ros2 action -h` imports this module.
    from rosidl_runtime_py.convert import message_to_yaml
    return first_line_indent + message_to_yaml(message)


class SendGoalVerb(VerbExtension):
    """Send an action goal."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the action name and type, the goal's YAML values (or --stdin) and -f/--feedback."""
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
        # Lazy: rosidl_runtime_py imports yaml and rosidl_parser, and `ros2 action -h` imports this module.
        from rosidl_runtime_py.set_message import FieldError, set_message_fields
        from rosidl_runtime_py.utilities import InvalidType, canonical_type, import_type

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
        # Lazy: rclpy and rosidl_runtime_py (yaml) import slowly; `ros2 action -h` imports this module.
        import rclpy
        from rclpy.action import ActionClient, get_action_names_and_types
        from rclpy.node import Node
        from rosidl_runtime_py.convert import message_to_yaml

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
