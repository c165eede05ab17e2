"""The launch description source of XML launch files."""

from launch_xml.launch_description_sources.xml_launch_description_source import XMLLaunchDescriptionSource

__all__ = ['XMLLaunchDescriptionSource']
