"""XMLLaunchDescriptionSource: an XML launch file."""

from launch.launch_description_sources import FrontendLaunchDescriptionSource

__all__ = ['XMLLaunchDescriptionSource']


class XMLLaunchDescriptionSource(FrontendLaunchDescriptionSource):
    format_name = 'xml'
