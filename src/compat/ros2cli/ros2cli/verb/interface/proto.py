"""`ros2 interface proto`: a default instance of an interface, as YAML."""

import argparse
from typing import Any

from ros2cli.completion import any_type_completer, with_completer
from ros2cli.verb import VerbExtension


def default_instance(type_name: str) -> Any:
    """A default message, service request or action goal for an interface name."""
    # Lazy: rosidl_runtime_py imports yaml and rosidl_parser, and `ros2 interface -h` imports this module.
    from rosidl_runtime_py.utilities import InvalidType, import_type
    parts = type_name.split('/')
    kind = parts[1] if len(parts) == 3 else 'msg'
    if kind not in ('msg', 'srv', 'action'):
        raise RuntimeError(f"Invalid name '{type_name}': the middle part must be 'msg', 'srv' or 'action'")
    try:
        type_class = import_type(type_name, kind)
    except InvalidType as error:
        raise RuntimeError(f"The passed interface type '{type_name}' is invalid: {error}") from None
    return {'msg': type_class, 'srv': getattr(type_class, 'Request', None),
            'action': getattr(type_class, 'Goal', None)}[kind]()


class ProtoVerb(VerbExtension):
    """Output an interface prototype."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the type and --no-quotes."""
        with_completer(parser.add_argument(
            'type', help="Show an interface definition (e.g. 'std_msgs/msg/String')"
        ), any_type_completer)
        parser.add_argument('--no-quotes', action='store_true', help='if true output has no outer quotes.')

    def main(self, *, args: argparse.Namespace) -> int:
        """Print a default instance as YAML, in double quotes unless --no-quotes.

        For a service it is the request, for an action the goal; an invalid name raises RuntimeError.
        """
        # Lazy: rosidl_runtime_py imports yaml and rosidl_parser, and `ros2 interface -h` imports this module.
        from rosidl_runtime_py.convert import message_to_yaml
        text = message_to_yaml(default_instance(args.type))
        print(text if args.no_quotes else f'"{text}"')
        return 0
