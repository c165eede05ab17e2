"""YAMLLaunchDescriptionSource: a YAML launch file."""

from launch.launch_description_sources.frontend_launch_description_source import (
    FrontendLaunchDescriptionSource,
)


class YAMLLaunchDescriptionSource(FrontendLaunchDescriptionSource):
    format_name = 'yaml'
