"""Descriptions of what an action runs, filled in when it executes."""

from launch.descriptions.executable import Executable

__all__ = ['Executable']
