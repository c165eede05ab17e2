"""What the verbs of `ros2 interface` share (upstream's ros2interface.api): kind filters, package errors."""

import argparse

from owl_common.hints import did_you_mean


def _add_kind_filters(parser: argparse.ArgumentParser) -> None:
    group = parser.add_mutually_exclusive_group()
    group.add_argument('-m', '--only-msgs', action='store_true', help='Print out only the messages')
    group.add_argument('-s', '--only-srvs', action='store_true', help='Print out only the services')
    group.add_argument('-a', '--only-actions', action='store_true', help='Print out only the actions')


def _wanted_kinds(args: argparse.Namespace) -> list[str]:
    chosen = [kind for kind, flag in (('msg', args.only_msgs), ('srv', args.only_srvs),
                                      ('action', args.only_actions)) if flag]
    return chosen or ['msg', 'srv', 'action']


def _unknown_package(package: str) -> str:
    # Lazy: rosidl_runtime_py imports yaml and rosidl_parser, and `ros2 interface -h` imports this module.
    from rosidl_runtime_py.get_interfaces import interface_index
    return f"Unknown package '{package}'{did_you_mean(package, interface_index())}"
