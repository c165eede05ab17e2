"""launch: the ROS 2 launch system (compatible re-implementation for Owl Kit Lab)."""

from launch import actions, conditions, event_handlers, events, launch_description_sources, substitutions
from launch.action import Action
from launch.condition import Condition
from launch.event import Event
from launch.event_handler import EventHandler
from launch.launch_context import LaunchContext
from launch.launch_description import LaunchDescription
from launch.launch_description_entity import LaunchDescriptionEntity
from launch.launch_description_source import LaunchDescriptionSource
from launch.launch_service import LaunchService
from launch.substitution import SomeSubstitutionsType, Substitution

__all__ = [
    'Action', 'Condition', 'Event', 'EventHandler', 'LaunchContext', 'LaunchDescription',
    'LaunchDescriptionEntity', 'LaunchDescriptionSource', 'LaunchService', 'SomeSubstitutionsType',
    'Substitution', 'actions', 'conditions', 'event_handlers', 'events', 'launch_description_sources',
    'substitutions',
]
