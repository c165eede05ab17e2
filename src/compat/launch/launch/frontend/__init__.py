"""XML and YAML launch files: tags become actions, `$(...)` values become substitutions."""

from launch.frontend import type_utils
from launch.frontend.entity import Entity, LaunchFileError
from launch.frontend.expose import expose_action, expose_substitution
from launch.frontend.parse_substitution import parse_substitution
from launch.frontend.parser import InvalidFrontendLaunchFileError, Parser, load_launch_file

__all__ = [
    'Entity', 'InvalidFrontendLaunchFileError', 'LaunchFileError', 'Parser', 'expose_action',
    'expose_substitution', 'load_launch_file', 'parse_substitution', 'type_utils',
]
