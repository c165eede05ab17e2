"""argcomplete completers for package, node, topic, service, action and type names.

Graph names come from the daemon when it runs (instant), else from a short-lived DirectNode.
Executable names are completed by ros2cli.api.run.executable_completer (it knows where `ros2 run`
looks for them).
"""

import argparse
from collections.abc import Callable, Iterable

from ament_index_python.packages import get_packages_with_prefixes
from owl_common.graph import full_node_name

from ros2cli.node.direct import DirectNode
from ros2cli.node.graph import Graph

# argcomplete calls a completer with the prefix and keyword arguments (parsed_args, action, parser);
# each completer takes the ones it needs.
Completer = Callable[..., Iterable[str]]


def with_completer(argument: argparse.Action, completer: Completer) -> argparse.Action:
    """The argument, with shell completion attached.

    argcomplete reads the `completer` attribute of the Action that add_argument returned
    (argparse's own Action has no such field, hence setattr).
    """
    setattr(argument, 'completer', completer)  # noqa: B010
    return argument


def package_completer(prefix: str, **_kwargs: object) -> Iterable[str]:
    """The names of the installed packages that start with prefix, sorted."""
    return sorted(p for p in get_packages_with_prefixes() if p.startswith(prefix))


def _graph_names(query: str, parsed_args: argparse.Namespace | None) -> list[str]:
    # Lazy: the verbs import this module.
    from ros2cli.daemon.client import DaemonGraph, is_daemon_running

    if is_daemon_running(timeout=1.0) and not getattr(parsed_args, 'no_daemon', False):
        graph: Graph = DaemonGraph()
        return _names_from(graph, query)
    with DirectNode(parsed_args) as direct:
        return _names_from(direct.graph, query)


def _names_from(graph: Graph, query: str) -> list[str]:
    if query == 'nodes':
        return sorted(full_node_name(ns, n) for n, ns in graph.node_names_and_namespaces())
    return [name for name, _ in getattr(graph, f'{query}_names_and_types')()]


def _graph_completer(query: str) -> Completer:
    def complete(prefix: str, parsed_args: argparse.Namespace | None = None, **_kwargs: object) -> list[str]:
        return [n for n in _graph_names(query, parsed_args) if n.startswith(prefix)]
    return complete


node_completer = _graph_completer('nodes')
topic_completer = _graph_completer('topic')
service_completer = _graph_completer('service')
action_completer = _graph_completer('action')


def _type_completer(kind: str) -> Completer:
    def complete(prefix: str, **_kwargs: object) -> list[str]:
        # Lazy: rosidl_runtime_py imports yaml and rosidl_parser, and the verbs import this module.
        from rosidl_runtime_py.get_interfaces import interface_index
        return [f'{package}/{kind}/{name}' for package, kinds in sorted(interface_index().items())
                for name in kinds[kind] if f'{package}/{kind}/{name}'.startswith(prefix)]
    return complete


message_type_completer = _type_completer('msg')
service_type_completer = _type_completer('srv')
action_type_completer = _type_completer('action')


def any_type_completer(prefix: str, **kwargs: object) -> list[str]:
    """Message, service and action type names ('pkg/msg/Name') that start with prefix."""
    return [*message_type_completer(prefix), *service_type_completer(prefix),
            *action_type_completer(prefix)]
