"""What the verbs of `ros2 param` share (upstream's ros2param.api): calls to a node's parameter services."""

import argparse
import re
import sys
from typing import TYPE_CHECKING, Any

from owl_common.hints import did_you_mean

from ros2cli.api.node import node_names
from ros2cli.completion import node_completer, with_completer
from ros2cli.node.direct import NAMED_LOOKUP_GRACE
from ros2cli.node.strategy import NodeStrategy, add_strategy_arguments
from ros2cli.service_call import DaemonServiceCaller, ServiceCaller, ServiceCallError, ServiceUnavailable

if TYPE_CHECKING:  # the messages are imported where they are used: `ros2 param -h` imports this module
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
        # Lazy: the message packages import slowly, and `ros2 param -h` imports this module.
        from rcl_interfaces.srv import ListParameters
        request = ListParameters.Request(prefixes=prefixes or [], depth=0)
        return sorted(self.call('list_parameters', ListParameters, request).result.names)

    def values(self, names: list[str]) -> list['ParameterValue']:
        """The ParameterValue of each name, in order; an empty list when the node lacks any of them."""
        from rcl_interfaces.srv import GetParameters  # lazy: see names()
        return list(self.call('get_parameters', GetParameters, GetParameters.Request(names=names)).values)

    def set(self, parameters: list['ParameterMsg']) -> list['SetParametersResult']:
        """Set the parameters on the node (NOT_SET deletes); a SetParametersResult for each, in order."""
        from rcl_interfaces.srv import SetParameters  # lazy: see names()
        request = SetParameters.Request(parameters=parameters)
        return list(self.call('set_parameters', SetParameters, request).results)

    def describe(self, name: str) -> list['ParameterDescriptor']:
        """The descriptor of one parameter, in a list; an empty list when the node has not declared it."""
        from rcl_interfaces.srv import DescribeParameters  # lazy: see names()
        request = DescribeParameters.Request(names=[name])
        return list(self.call('describe_parameters', DescribeParameters, request).descriptors)

    def unknown(self, name: str) -> str:
        """' (did you mean ...)' for an undeclared parameter name."""
        return did_you_mean(name, self.names())

    def close(self) -> None:
        """Close the NodeStrategy if this session made it; one that was passed in is the caller's to close."""
        if self._strategy is not None and self._owns_strategy:
            self._strategy.close()
        self._strategy = None

    def __exit__(self, *exc: object) -> None:
        self.close()


def _add_common(parser: argparse.ArgumentParser, node_required: bool = True, timeout: bool = True) -> None:
    with_completer(parser.add_argument('node_name', nargs=None if node_required else '?',
                        help='Name of the ROS node'), node_completer)
    parser.add_argument('--include-hidden-nodes', action='store_true', help='Consider hidden nodes as well')
    if timeout:
        parser.add_argument('--timeout', metavar='N', type=int, default=1,
                            help='Wait for N seconds until node is found (default: 1 second)')
    add_strategy_arguments(parser)


def _set_one(args: argparse.Namespace, session: ParameterSession, value: Any, verb: tuple[str, str]) -> None:
    # Lazy: the message packages import slowly, and `ros2 param -h` imports this module.
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
    # Lazy: rclpy is slow to import, and `ros2 param -h` imports this module.
    from rclpy.parameter import Parameter
    wrong_type = re.fullmatch(r"Wrong parameter type, expected 'Type\.(\w+)' got 'Type\.(\w+)'", reason)
    if wrong_type:
        expected, got = (TYPE_NAMES[Parameter.Type[n].value] if n in Parameter.Type.__members__ else n
                         for n in wrong_type.groups())
        return f"Wrong parameter type for '{name}': expected {expected}, got {got}"
    if 'undeclared parameter' in reason:
        return f"node '{session.node_name}' has no parameter '{name}'{session.unknown(name)}"
    return reason or 'no reason given'
