"""The verbs of `ros2 doctor` (entry point group 'ros2doctor.verb'): hello.

Their base class is ros2cli's VerbExtension, under the name upstream's ros2doctor.verb gives it.
"""

from ros2cli.verb import VerbExtension

__all__ = ['VerbExtension']
