"""Run a node until Ctrl-C or an external shutdown, then exit quietly with code 0."""

import signal
import sys
from collections.abc import Callable

import rclpy
from rclpy.exceptions import NameValidationException, ParameterException
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.signals import SignalHandlerOptions

# What a node's constructor raises for a bad --ros-args parameter or name: a user error.
STARTUP_ERRORS = (ParameterException, NameValidationException, ValueError)
SIGNAL_POLL = 0.1  # s: the longest a Ctrl-C waits for the executor to return to Python


def ignore_further_interrupts() -> None:
    """Let cleanup finish: a second SIGINT (a group Ctrl-C plus a launcher's forwarded one) or a
    SIGTERM must not turn a clean exit into a traceback."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)


def spin_node(make_node: Callable[[], Node], args: list[str] | None = None) -> None:
    """Initialise rclpy, spin the node make_node() builds, and clean up on every exit path.

    A bad startup parameter ends the process with one error line and exit code 2.
    """
    # Ctrl-C and SIGTERM raise KeyboardInterrupt in this thread (Python's handlers), never rclpy's
    # handler: that one invalidates the context from another thread, which raced whatever this
    # thread was doing — building the node or the executor, or spinning (RCLError "context is not
    # valid", a pybind conversion error, or a segfault; up to 1 in 10 stops in stress runs).
    # Waiting at most SIGNAL_POLL at a time lets the interrupt through promptly.
    rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)
    signal.signal(signal.SIGTERM, signal.default_int_handler)
    node = None
    try:
        node = make_node()
        executor = rclpy.get_global_executor()
        executor.add_node(node)
        while rclpy.ok():
            executor.spin_once(timeout_sec=SIGNAL_POLL)
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
