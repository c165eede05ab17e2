"""`ros2 param dump`: all of a node's parameters as a parameter file."""

import argparse
from typing import TYPE_CHECKING, Any

from ros2cli.api.param import ParameterSession, _add_common, python_value
from ros2cli.verb import VerbExtension

if TYPE_CHECKING:  # the messages are imported where they are used: `ros2 param -h` imports this module
    from rcl_interfaces.msg import ParameterValue


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
        import yaml  # lazy: slow to import, and `ros2 param -h` imports this module
        with ParameterSession(args, args.node_name) as session:
            names = session.names()
            values = session.values(names) if names else []
        document = {session.node_name: {'ros__parameters': nested_parameters(names, values)}}
        print(yaml.dump(document, default_flow_style=False))
        return 0
