"""`ros2 param list | get | set | delete | describe | dump | load`, through the nodes' parameter services."""

import argparse
import sys
from typing import TYPE_CHECKING, Any

from ros2cli.command import VerbCommand
from ros2cli.verb import VerbExtension

if TYPE_CHECKING:  # the messages are imported where they are used: `ros2 -h` imports this module
    from rcl_interfaces.msg import Parameter as ParameterMsg
    from rcl_interfaces.msg import ParameterDescriptor, ParameterValue, SetParametersResult

SERVICE_TIMEOUT = 5.0
TYPE_NAMES = {0: 'not set', 1: 'boolean', 2: 'integer', 3: 'double', 4: 'string', 5: 'byte array',
              6: 'boolean array', 7: 'integer array', 8: 'double array', 9: 'string array'}
VALUE_LABELS = {1: 'Boolean value is:', 2: 'Integer value is:', 3: 'Double value is:', 4: 'String value is:',
                5: 'Byte values are:', 6: 'Boolean values are:', 7: 'Integer values are:',
                8: 'Double values are:', 9: 'String values are:'}


def full_name(node_name: str) -> str:
    """The node name made absolute: '/' put in front when missing (no namespace is applied)."""
    return node_name if node_name.startswith('/') else '/' + node_name


# ParameterValue's field for each of its types (rcl_interfaces/msg/ParameterType), 0 being NOT_SET.
VALUE_FIELDS = ('', 'bool_value', 'integer_value', 'double_value', 'string_value', 'byte_array_value',
                'bool_array_value', 'integer_array_value', 'double_array_value', 'string_array_value')


def python_value(value: 'ParameterValue') -> Any:
    """The value a ParameterValue holds, arrays as lists; None when it is not set.

    This is what rclpy's parameter_value_to_python gives, without importing rclpy (a fifth of a
    warm `param get`'s time). ValueError for a type number that does not exist.
    """
    if not 0 <= value.type < len(VALUE_FIELDS):
        raise ValueError(f'unknown parameter type {value.type}')
    if not value.type:
        return None
    held = getattr(value, VALUE_FIELDS[value.type])
    return list(held) if VALUE_FIELDS[value.type].endswith('_array_value') else held


def value_text(value: 'ParameterValue') -> str:
    """What `param get` prints after the label (Python's str of the value)."""
    return str(python_value(value))


class ParameterSession:
    """Parameter service calls to one node, once NodeStrategy has found it in the graph.

    With a daemon the daemon's warm node makes the calls; otherwise a DirectNode does.
    """

    def __init__(self, args: argparse.Namespace, node_name: str, wait: float | None = None,
                 strategy: Any = None) -> None:
        self.args = args
        self.node_name = full_name(node_name)
        self.wait = getattr(args, 'timeout', 1) if wait is None else wait
        self._strategy: Any = strategy
        self._owns_strategy = strategy is None
        self._caller: Any = None

    def __enter__(self) -> 'ParameterSession':
        from owl_common.hints import did_you_mean

        from ros2cli.api.node import node_names
        from ros2cli.node.direct import NAMED_LOOKUP_GRACE
        from ros2cli.node.strategy import NodeStrategy
        from ros2cli.service_call import DaemonServiceCaller, ServiceCaller

        if self._strategy is None:
            self._strategy = NodeStrategy(self.args, spin_time=0.0)
        hidden = getattr(self.args, 'include_hidden_nodes', False)
        graph = self._strategy.graph
        # A DirectNode may need the discovery grace (see NAMED_LOOKUP_GRACE) beyond --timeout.
        direct = not self._strategy.uses_daemon and self.wait
        wait = max(self.wait, NAMED_LOOKUP_GRACE) if direct else self.wait
        if not self._strategy.wait_until(lambda: self.node_name in node_names(graph, hidden), wait):
            hint = did_you_mean(self.node_name, node_names(graph, hidden))
            self.close()
            raise RuntimeError(f'Node not found{hint}')
        self._caller = (DaemonServiceCaller(SERVICE_TIMEOUT) if self._strategy.uses_daemon
                        else ServiceCaller(self._strategy.direct.node))
        return self

    def call(self, service: str, srv_class: Any, request: Any) -> Any:
        """The response of one of the node's parameter services (`service`: e.g. 'get_parameters').

        RuntimeError, with upstream's message, when the service is not available or the call fails.
        """
        from ros2cli.service_call import ServiceCallError, ServiceUnavailable
        try:
            return self._caller.call(f'{self.node_name}/{service}', srv_class, request, SERVICE_TIMEOUT)
        except ServiceUnavailable:
            raise RuntimeError('Wait for service timed out waiting for parameter services for node '
                               f'{self.node_name}') from None
        except ServiceCallError as error:
            raise RuntimeError(f"Exception while calling {service} service of node '{self.node_name}': "
                               f'{error}') from None

    def names(self, prefixes: list[str] | None = None) -> list[str]:
        """The node's parameter names, sorted (only those under `prefixes`, when given)."""
        from rcl_interfaces.srv import ListParameters
        request = ListParameters.Request(prefixes=prefixes or [], depth=0)
        return sorted(self.call('list_parameters', ListParameters, request).result.names)

    def values(self, names: list[str]) -> list['ParameterValue']:
        """The ParameterValue of each name, in order; an empty list when the node lacks any of them."""
        from rcl_interfaces.srv import GetParameters
        return list(self.call('get_parameters', GetParameters, GetParameters.Request(names=names)).values)

    def set(self, parameters: list['ParameterMsg']) -> list['SetParametersResult']:
        """Set the parameters on the node (NOT_SET deletes); a SetParametersResult for each, in order."""
        from rcl_interfaces.srv import SetParameters
        request = SetParameters.Request(parameters=parameters)
        return list(self.call('set_parameters', SetParameters, request).results)

    def describe(self, name: str) -> list['ParameterDescriptor']:
        """The descriptor of one parameter, in a list; an empty list when the node has not declared it."""
        from rcl_interfaces.srv import DescribeParameters
        request = DescribeParameters.Request(names=[name])
        return list(self.call('describe_parameters', DescribeParameters, request).descriptors)

    def unknown(self, name: str) -> str:
        """' (did you mean ...)' for an undeclared parameter name."""
        from owl_common.hints import did_you_mean
        return did_you_mean(name, self.names())

    def close(self) -> None:
        """Close the NodeStrategy if this session made it; one that was passed in is the caller's to close."""
        if self._strategy is not None and self._owns_strategy:
            self._strategy.close()
        self._strategy = None

    def __exit__(self, *exc: object) -> None:
        self.close()


def _add_common(parser: argparse.ArgumentParser, node_required: bool = True, timeout: bool = True) -> None:
    from ros2cli.completion import node_completer, with_completer
    from ros2cli.node.strategy import add_strategy_arguments
    with_completer(parser.add_argument('node_name', nargs=None if node_required else '?',
                        help='Name of the ROS node'), node_completer)
    parser.add_argument('--include-hidden-nodes', action='store_true', help='Consider hidden nodes as well')
    if timeout:
        parser.add_argument('--timeout', metavar='N', type=int, default=1,
                            help='Wait for N seconds until node is found (default: 1 second)')
    add_strategy_arguments(parser)


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
        import re

        from ros2cli.api.node import node_names
        from ros2cli.node.strategy import NodeStrategy

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


class GetVerb(VerbExtension):
    """Get parameter."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the common node options, the parameter name and --hide-type."""
        _add_common(parser)
        parser.add_argument('parameter_name', help='Name of the parameter')
        parser.add_argument('--hide-type', action='store_true', help='Hide the type information')

    def main(self, *, args: argparse.Namespace) -> int | str:
        """Print the value after its type's label ('Integer value is: 3'), or the value alone for --hide-type.

        An undeclared parameter gives the error message, with a 'did you mean' hint.
        """
        with ParameterSession(args, args.node_name) as session:
            values = session.values([args.parameter_name])
            if not values:
                return (f"Parameter not set: node '{session.node_name}' has no parameter "
                        f"'{args.parameter_name}'{session.unknown(args.parameter_name)}")
        value = values[0]
        if value.type == 0:
            print('Parameter not set.')
            return 0
        if value.type not in VALUE_LABELS:
            return f"Unknown parameter type '{value.type}'"
        text = value_text(value)
        print(text if args.hide_type else f'{VALUE_LABELS[value.type]} {text}')
        return 0


def _set_one(args: argparse.Namespace, session: ParameterSession, value: Any, verb: tuple[str, str]) -> None:
    from rcl_interfaces.msg import Parameter
    result = session.set([Parameter(name=args.parameter_name, value=value)])[0]
    if result.successful:
        print(verb[0] + (f': {result.reason}' if result.reason else ''))
        return
    print(f'{verb[1]}: {failure_reason(result.reason, args.parameter_name, session)}', file=sys.stderr)


def failure_reason(reason: str, name: str, session: ParameterSession) -> str:
    """Rclpy's reason for a refused parameter, said plainly.

    The course's type names replace rclpy's enum names, an undeclared name gets the closest
    declared one as a hint, and an empty reason becomes 'no reason given'.
    """
    import re

    from rclpy.parameter import Parameter
    wrong_type = re.fullmatch(r"Wrong parameter type, expected 'Type\.(\w+)' got 'Type\.(\w+)'", reason)
    if wrong_type:
        expected, got = (TYPE_NAMES[Parameter.Type[n].value] if n in Parameter.Type.__members__ else n
                         for n in wrong_type.groups())
        return f"Wrong parameter type for '{name}': expected {expected}, got {got}"
    if 'undeclared parameter' in reason:
        return f"node '{session.node_name}' has no parameter '{name}'{session.unknown(name)}"
    return reason or 'no reason given'


class SetVerb(VerbExtension):
    """Set parameter."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the common node options, the parameter name and its value (YAML: '3' is an integer)."""
        _add_common(parser)
        parser.add_argument('parameter_name', help='Name of the parameter')
        parser.add_argument('value', help='Value of the parameter')

    def main(self, *, args: argparse.Namespace) -> int:
        """Set the parameter and print the outcome; a refusal goes to stderr (exit code 0, as upstream)."""
        from rclpy.parameter import get_parameter_value
        with ParameterSession(args, args.node_name) as session:
            _set_one(args, session, get_parameter_value(args.value),
                     ('Set parameter successful', 'Setting parameter failed'))
        return 0


class DeleteVerb(VerbExtension):
    """Delete parameter."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the common node options and the parameter name."""
        _add_common(parser)
        parser.add_argument('parameter_name', help='Name of the parameter')

    def main(self, *, args: argparse.Namespace) -> int:
        """Delete the parameter (set it NOT_SET) and print the outcome; a refusal is explained on stderr."""
        from rcl_interfaces.msg import ParameterValue
        with ParameterSession(args, args.node_name) as session:
            _set_one(args, session, ParameterValue(type=0),
                     ('Deleted parameter successfully', 'Deleting parameter failed'))
        return 0


class DescribeVerb(VerbExtension):
    """Show descriptive information about declared parameters."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the common node options and one or more parameter names."""
        _add_common(parser)
        parser.add_argument('parameter_names', nargs='+', help='Names of the parameters')

    def main(self, *, args: argparse.Namespace) -> int:
        """Print each declared parameter's type, description and constraints.

        Names the node has not declared are reported afterwards on stderr, with a 'did you mean' hint; the
        exit code is 0 all the same.
        """
        with ParameterSession(args, args.node_name) as session:
            # One request per name: a node answers nothing at all when any name is undeclared.
            descriptors, hints = [], {}
            for name in args.parameter_names:
                found = session.describe(name)
                descriptors += found
                if not found:
                    hints[name] = session.unknown(name)
        for descriptor in descriptors:
            print(f'Parameter name: {descriptor.name}')
            print(f'  Type: {TYPE_NAMES.get(descriptor.type, descriptor.type)}')
            if descriptor.description:
                print(f'  Description: {descriptor.description}')
            print('  Constraints:')
            if descriptor.read_only:
                print('    Read only: true')
            ranges = list(descriptor.floating_point_range) or list(descriptor.integer_range)
            if ranges:
                print(f'    Min value: {ranges[0].from_value}')
                print(f'    Max value: {ranges[0].to_value}')
                if ranges[0].step != 0:
                    print(f'    Step: {ranges[0].step}')
            if descriptor.additional_constraints:
                print(f'    Additional constraints: {descriptor.additional_constraints}')
        for name, hint in hints.items():
            print(f"Parameter '{name}' is not declared by node '{session.node_name}'{hint}", file=sys.stderr)
        return 0


def nested_parameters(names: list[str], values: list['ParameterValue']) -> dict[str, Any]:
    """{'a.b': 1} -> {'a': {'b': 1}}, the shape of a parameter file."""
    tree: dict[str, Any] = {}
    for name, value in zip(names, values, strict=True):
        *path, leaf = name.split('.')
        branch = tree
        for part in path:
            branch = branch.setdefault(part, {})
        branch[leaf] = python_value(value)
    return tree


class DumpVerb(VerbExtension):
    """Show all of the parameters of a node in a YAML file format."""

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the common node options."""
        _add_common(parser)

    def main(self, *, args: argparse.Namespace) -> int:
        """Print all of the node's parameters as a parameter file (YAML `<node>: ros__parameters: ...`)."""
        import yaml
        with ParameterSession(args, args.node_name) as session:
            names = session.names()
            values = session.values(names) if names else []
        document = {session.node_name: {'ros__parameters': nested_parameters(names, values)}}
        print(yaml.dump(document, default_flow_style=False))
        return 0


def parameters_for_node(path: str, node_name: str, use_wildcard: bool) -> list['ParameterMsg']:
    """The Parameter messages a parameter file holds for one node.

    The '/**' entry (when used) is read first, then the node's own entry, which overrides it
    (rclpy's parameter_dict_from_yaml_file reads them). RuntimeError with one line when the file
    cannot be read or nothing in it fits.
    """
    from owl_common.hints import did_you_mean
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


class ParamCommand(VerbCommand):
    """Various param related sub-commands."""

    VERB_GROUP = 'ros2param.verb'
