"""YAML launch files: the `yaml` parser of launch's frontend and the YAML launch description source."""

from launch_yaml import launch_description_sources
from launch_yaml.entity import Entity
from launch_yaml.parser import Parser

__all__ = ['Entity', 'Parser', 'launch_description_sources']
