"""The launch description source of YAML launch files."""

from launch_yaml.launch_description_sources.yaml_launch_description_source import YAMLLaunchDescriptionSource

__all__ = ['YAMLLaunchDescriptionSource']
