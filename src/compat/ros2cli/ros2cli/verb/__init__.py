"""`ros2 <command> <verb>`: the verb extension point.

Its entry point groups are '<package>.verb', e.g. 'ros2topic.verb'.

A verb is a class with a docstring (its first line is what `ros2 <command> -h` lists),
    add_arguments(self, parser, cli_name) -> None   its options
    main(self, *, args) -> int | str | None         its work (see ros2cli.cli for the result)
registered under its name in its command's verb group.
"""

from __future__ import annotations

import argparse
from typing import Any

from ros2cli.plugin_system import PLUGIN_SYSTEM_VERSION, instantiate_extensions, satisfies_version


class VerbExtension:
    """The extension point for a command's verbs (the base class of a verb)."""

    NAME: str | None = None
    EXTENSION_POINT_VERSION = '0.1'

    def __init__(self) -> None:
        satisfies_version(PLUGIN_SYSTEM_VERSION, '^0.1')

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """Add the verb's options to its parser; by default it has none."""
        pass

    def main(self, *, args: argparse.Namespace) -> int | str | None:
        """Do the verb's work; every verb must override it (see ros2cli.cli for the result)."""
        raise NotImplementedError


def get_verb_extensions(name: str) -> dict[str, Any]:
    """Every verb of the group `name`, instantiated (upstream's name; loads all of them)."""
    return instantiate_extensions(name)
