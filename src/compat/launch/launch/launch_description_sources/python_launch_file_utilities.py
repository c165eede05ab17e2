"""Loading Python launch files: the module, and the description its generate_launch_description() returns."""

from __future__ import annotations

import importlib.machinery
import importlib.util

from launch.launch_description import LaunchDescription


class InvalidPythonLaunchFileError(Exception):
    pass


def load_python_launch_file_as_module(python_launch_file_path: str) -> object:
    """Execute the file as a fresh module named python_launch_file, with __file__ set."""
    loader = importlib.machinery.SourceFileLoader('python_launch_file', python_launch_file_path)
    spec = importlib.util.spec_from_loader('python_launch_file', loader)
    assert spec is not None
    module = importlib.util.module_from_spec(spec)
    loader.exec_module(module)
    return module


def get_launch_description_from_python_launch_file(python_launch_file_path: str) -> LaunchDescription:
    module = load_python_launch_file_as_module(python_launch_file_path)
    generate = getattr(module, 'generate_launch_description', None)
    if not callable(generate):
        raise InvalidPythonLaunchFileError(
            f"launch file at '{python_launch_file_path}' does not contain the required function "
            "'generate_launch_description()'")
    description = generate()
    if not isinstance(description, LaunchDescription):
        raise InvalidPythonLaunchFileError(
            f"generate_launch_description() of launch file at '{python_launch_file_path}' returned "
            f"'{type(description).__name__}' instead of a launch.LaunchDescription")
    return description
