"""Run a node until Ctrl-C or an external shutdown, then exit quietly with code 0."""

import signal
import sys
from collections.abc import Callable

import rclpy
from rclpy.exceptions import NameValidationException, ParameterException
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node

# What a node's constructor raises for a bad --ros-args parameter or name: a user error.
STARTUP_ERRORS = (ParameterException, NameValidationException, ValueError)


def ignore_further_interrupts() -> None:
    """Let cleanup finish: a second SIGINT (a group Ctrl-C plus a launcher's forwarded one)
    must not turn a clean exit into a traceback."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def spin_node(make_node: Callable[[], Node], args: list[str] | None = None) -> None:
    """Initialise rclpy, spin the node make_node() builds, and clean up on every exit path.

    A bad startup parameter ends the process with one error line and exit code 2.
    """
    rclpy.init(args=args)
    node = None
    try:
        node = make_node()
        rclpy.spin(node)
    except STARTUP_ERRORS as error:
        if node is not None:
            raise
        print(f'error: {error}', file=sys.stderr)
        rclpy.try_shutdown()
        sys.exit(2)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass  # Ctrl-C is how the course stops nodes: no traceback.
    finally:
        ignore_further_interrupts()
        if node is not None:
            node.destroy_node()
        rclpy.try_shutdown()
