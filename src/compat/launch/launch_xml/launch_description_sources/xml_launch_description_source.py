"""XMLLaunchDescriptionSource: an XML launch file."""

from launch.launch_description_sources import FrontendLaunchDescriptionSource


class XMLLaunchDescriptionSource(FrontendLaunchDescriptionSource):
    format_name = 'xml'
