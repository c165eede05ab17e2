"""Loading XML and YAML launch files through the frontend."""

from __future__ import annotations

from typing import TYPE_CHECKING

from launch.frontend.parser import InvalidFrontendLaunchFileError, Parser

if TYPE_CHECKING:
    from launch.launch_description import LaunchDescription


def get_launch_description_from_frontend_launch_file(frontend_launch_file_path: str, *,
                                                     parser: type[Parser] = Parser) -> LaunchDescription:
    """Read an XML or YAML launch file with parser (by default: format by extension, else tried as both)."""
    try:
        root, parser_instance = parser.load(frontend_launch_file_path)
    except Exception as error:
        extension = parser.get_file_extension_from_filename(frontend_launch_file_path)
        raise InvalidFrontendLaunchFileError(extension, likely_errors=[error]) from error
    return parser_instance.parse_description(root)
