"""Publish and subscribe: talker and listener on `chatter`."""
