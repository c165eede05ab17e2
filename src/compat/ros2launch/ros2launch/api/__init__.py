"""What `ros2 launch` does, as plain functions (ros2launch.api.api), under upstream's package name.

Importing it imports `launch`, which takes a while: ros2launch.command.launch imports it only when
`ros2 launch` runs.
"""

from ros2launch.api.api import (
    MultipleLaunchFilesError,
    format_arguments_of_launch_file,
    format_launch_description,
    get_share_file_path_from_package,
    launch_a_launch_file,
    load_launch_file,
    parse_launch_arguments,
)

__all__ = [
    'MultipleLaunchFilesError',
    'format_arguments_of_launch_file',
    'format_launch_description',
    'get_share_file_path_from_package',
    'launch_a_launch_file',
    'load_launch_file',
    'parse_launch_arguments',
]
