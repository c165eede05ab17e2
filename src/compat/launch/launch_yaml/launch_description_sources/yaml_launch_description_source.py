"""YAMLLaunchDescriptionSource: a YAML launch file."""

from launch.launch_description_sources import FrontendLaunchDescriptionSource


class YAMLLaunchDescriptionSource(FrontendLaunchDescriptionSource):
    format_name = 'yaml'
