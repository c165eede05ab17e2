"""The base class of launch events."""


class Event:
    """Something that happened during a launch; event handlers react to it."""

    name = 'launch.Event'
