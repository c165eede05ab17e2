"""`ros2 param load`: set a node's parameters from a parameter file."""

import argparse
import sys
from typing import TYPE_CHECKING, Any

from owl_common.hints import did_you_mean

from ros2cli.api.param import ParameterSession, _add_common, full_name
from ros2cli.verb import VerbExtension

if TYPE_CHECKING:  # the messages are imported where they are used: `ros2 param -h` imports this module
    from rcl_interfaces.msg import Parameter as ParameterMsg


def parameters_for_node(path: str, node_name: str, use_wildcard: bool) -> list['ParameterMsg']:
    """The Parameter messages a parameter file holds for one node.

    The '/**' entry (when used) is read first, then the node's own entry, which overrides it
    (rclpy's parameter_dict_from_yaml_file reads them). RuntimeError with one line when the file
    cannot be read or nothing in it fits.
    """
    # Lazy: rclpy is slow to import, and `ros2 param -h` imports this module.
    from rclpy.parameter import parameter_dict_from_yaml_file

    document = read_parameter_file(path)  # its YAML errors and shape, said in one line
    if not isinstance(document, dict):
        raise RuntimeError('the file is not a ROS parameter file (expected '
                           "'<node>: ros__parameters: ...' as written by `ros2 param dump`)")
    namespace, _, base = node_name.rpartition('/')
    keys = (['/**'] if use_wildcard else []) + [node_name] + ([base] if not namespace else [])
    present = [key for key in dict.fromkeys(keys) if key in document]
    if not present:
        nodes = [str(k) for k in document]
        raise RuntimeError(f'Param file does not contain selected parameters: nothing for {node_name}'
                           f"{did_you_mean(node_name, nodes)}; it has: {', '.join(nodes) or 'no nodes'}")
    try:
        return list(parameter_dict_from_yaml_file(path, target_nodes=present).values())
    except (TypeError, ValueError) as error:  # a value rclpy cannot make a parameter of
        raise RuntimeError(f"'{path}': {' '.join(str(error).split())}") from None


def read_parameter_file(path: str) -> Any:
    """The parsed YAML of a parameter file; RuntimeError with one line when it cannot be read."""
    # Lazy: rosidl_runtime_py imports yaml and rosidl_parser, and `ros2 param -h` imports this module.
    from rosidl_runtime_py.set_message import FieldError, parse_yaml
    try:
        with open(path, encoding='utf-8') as parameter_file:
            text = parameter_file.read()
    except FileNotFoundError:
        raise RuntimeError(f"No such file or directory: '{path}'") from None
    except OSError as error:
        raise RuntimeError(f"Cannot read '{path}': {error.strerror}") from None
    try:
        return parse_yaml(text)
    except FieldError as error:
        raise RuntimeError(f"'{path}': {str(error).split(': ' + repr(text))[0]}") from None


class LoadVerb(VerbExtension):
    """Load parameter file for a node."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the common node options, the parameter file and --no-use-wildcard."""
        _add_common(parser)
        parser.add_argument('parameter_file', help='Parameter file')
        parser.add_argument('--no-use-wildcard', action='store_true',
                            help="Do not load parameters in the '/**' namespace into the node")

    def main(self, *, args: argparse.Namespace) -> int:
        """Set the node's parameters from the file and print one outcome line per parameter.

        The file's '/**' entry counts too unless --no-use-wildcard (the node's own entry wins over it).
        Failures go to stderr and the exit code is 0, as upstream.
        """
        parameters = parameters_for_node(args.parameter_file, full_name(args.node_name),
                                         not args.no_use_wildcard)
        with ParameterSession(args, args.node_name) as session:
            results = session.set(parameters)
        for parameter, result in zip(parameters, results, strict=True):
            reason = f': {result.reason}' if result.reason else ''
            if result.successful:
                print(f'Set parameter {parameter.name} successful{reason}')
            else:
                print(f'Set parameter {parameter.name} failed{reason}', file=sys.stderr)
        return 0
