"""XMLLaunchDescriptionSource: an XML launch file."""

from launch.launch_description_sources.frontend_launch_description_source import (
    FrontendLaunchDescriptionSource,
)


class XMLLaunchDescriptionSource(FrontendLaunchDescriptionSource):
    format_name = 'xml'
