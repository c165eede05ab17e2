"""Loading XML and YAML launch files through the frontend."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.frontend.parser import InvalidFrontendLaunchFileError, Parser

if TYPE_CHECKING:
    from launch.launch_description import LaunchDescription


def get_launch_description_from_frontend_launch_file(frontend_launch_file_path: str) -> LaunchDescription:
    """Read an XML or YAML launch file (format by extension, else tried as both)."""
    try:
        root, parser = Parser.load(frontend_launch_file_path)
    except Exception as error:
        raise InvalidFrontendLaunchFileError(str(error)) from error
    return parser.parse_description(root)
