"""AnonName: a name made unique for this launch."""

from __future__ import annotations

import os
import random
import socket
from typing import TYPE_CHECKING

from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution, describe_substitutions
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions

if TYPE_CHECKING:
    from launch.launch_context import LaunchContext


class AnonName(Substitution):
    """<name>_<host>_<pid>_<random>, the same for the same name throughout one launch."""

    def __init__(self, name: SomeSubstitutionsType) -> None:
        self.name = normalize_to_list_of_substitutions(name)

    def perform(self, context: LaunchContext) -> str:
        name = perform_substitutions(context, self.name)
        key = 'anon' + name
        if key not in context.launch_configurations:
            raw = f'{name}_{socket.gethostname()}_{os.getpid()}_{random.randint(0, 2 ** 63)}'
            context.launch_configurations[key] = raw.replace('.', '_').replace('-', '_').replace(':', '_')
        return context.launch_configurations[key]

    def describe(self) -> str:
        return f'AnonName({describe_substitutions(self.name)})'
