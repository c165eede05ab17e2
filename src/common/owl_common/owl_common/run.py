"""Run a node until Ctrl-C or an external shutdown, then exit quietly with code 0 (1 if clean-up hangs)."""

import faulthandler
import gc
import signal
import sys
from collections.abc import Callable

import rclpy
from rclpy.exceptions import NameValidationException, ParameterException
from rclpy.executors import ExternalShutdownException
from rclpy.experimental import EventsExecutor
from rclpy.node import Node
from rclpy.signals import SignalHandlerOptions

# What a node's constructor raises for a bad --ros-args parameter or name: a user error.
STARTUP_ERRORS = (ParameterException, NameValidationException, ValueError)
SIGNAL_POLL = 0.1  # s: the longest a Ctrl-C waits for the executor to return to Python
# s: the most clean-up may take (normally well under 1 s). Fast DDS can deadlock while it tears a
# participant down (the eProsima/Fast-DDS#6502 shape); signals are ignored by then, so without
# a limit the process hangs until SIGKILL. faulthandler's watchdog is a C thread: it works even
# while the blocked call holds the GIL, prints every thread's stack and exits with code 1.
TEARDOWN_LIMIT = 5.0


def begin_cleanup() -> None:
    """Call when a process starts its final clean-up (destroying its nodes, shutting rclpy down).

    A second SIGINT (a group Ctrl-C plus a launcher's forwarded one) or a SIGTERM must not turn a
    clean exit into a traceback, so both are ignored from here on; and a clean-up that hangs ends
    the process after TEARDOWN_LIMIT s with every thread's stack and exit code 1. The watchdog is
    never cancelled: the participant may also be torn down at interpreter exit.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    faulthandler.dump_traceback_later(TEARDOWN_LIMIT, exit=True)


class StopRequest:
    """SIGINT/SIGTERM handler: a stop request the main loop polls, an exception before it polls.

    While the main loop runs, raising KeyboardInterrupt from the handler can land anywhere in the
    main thread, including inside a __del__ (rclpy's Future has one), where Python prints it as an
    "Exception ignored" traceback and swallows it, so the process would not stop. Before the loop
    (node construction) an exception is the only way to interrupt a blocking call.
    """

    def __init__(self) -> None:
        self.requested = False
        self.polling = False

    def __call__(self, signum: int, frame: object) -> None:
        """Record the stop request; raise KeyboardInterrupt too unless the main loop polls for it."""
        self.requested = True
        if not self.polling:
            raise KeyboardInterrupt

    def install(self) -> None:
        """Make this the process's SIGINT and SIGTERM handler."""
        signal.signal(signal.SIGINT, self)
        signal.signal(signal.SIGTERM, self)


def init_with_stop_request(args: list[str] | None = None) -> StopRequest:
    """rclpy.init with Ctrl-C and SIGTERM handled in the main thread by the returned StopRequest.

    Never rclpy's own handler: it invalidates the context from another thread, which raced whatever
    the main thread was doing: building the node or the executor, or spinning (RCLError "context
    is not valid", a pybind conversion error, or a segfault; up to 1 in 10 stops in stress runs).
    The caller's loop must return to Python every SIGNAL_POLL or so to see the request.
    """
    rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)
    stop = StopRequest()
    stop.install()
    return stop


def spin_until_stopped(node: Node | list[Node], stop: StopRequest, events: bool = False) -> None:
    """rclpy.spin(node) for a process started with init_with_stop_request (one node or several).

    Returns when ROS shuts down; raises KeyboardInterrupt at a stop request (Ctrl-C, SIGTERM), from
    here and never from inside rclpy, so a node's own clean-up (after `except KeyboardInterrupt`,
    as in the course) still has a working ROS.

    events=True spins with rclpy's EventsExecutor: rmw calls it back per message, where the
    default executor rebuilds a wait set of every entity of the node for each message (robot_view,
    idle with 12 subscriptions, 9 clients and 4 timers: 50 % of a core, 12 % with it). It takes
    no guard conditions, ignores callback groups, and (rclpy 7.1.5) fails on a subscription whose
    callback takes the message's info: only nodes without these may use it.
    """
    # From here a stop is only recorded: a KeyboardInterrupt raised inside the executor's
    # constructor would leave a half-made executor whose __del__ prints a traceback (a Ctrl-C just
    # after rqt printed its address did, in one make test run).
    stop.polling = True
    nodes = node if isinstance(node, list) else [node]
    executor = EventsExecutor() if events else rclpy.get_global_executor()
    for each in nodes:
        executor.add_node(each)
    try:
        while rclpy.ok() and not stop.requested:
            executor.spin_once(timeout_sec=SIGNAL_POLL)
    finally:
        for each in nodes:
            executor.remove_node(each)
        if events:  # its rmw callbacks go before the nodes' entities do
            executor.shutdown()
    if stop.requested:
        raise KeyboardInterrupt


def spin_node(make_node: Callable[[], Node | list[Node]], args: list[str] | None = None,
              events: bool = False) -> None:
    """Initialise rclpy, spin the node (or nodes) make_node() builds, and clean up on every exit path.

    A bad startup parameter ends the process with one error line and exit code 2. events: see
    spin_until_stopped.
    """
    stop = init_with_stop_request(args)
    nodes: list[Node] = []
    try:
        made = make_node()
        nodes = made if isinstance(made, list) else [made]
        # What the start built (modules, the node, its page) lives as long as the process: kept out
        # of the collector's rounds, the last one at exit included (a simulated module's stop spent
        # most of its 0.1-0.15 s of CPU there).
        gc.freeze()
        spin_until_stopped(nodes, stop, events)
    except STARTUP_ERRORS as error:
        if nodes:
            raise
        print(f'error: {error}', file=sys.stderr)
        rclpy.try_shutdown()
        sys.exit(2)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass  # Ctrl-C is how the course stops nodes: no traceback.
    finally:
        begin_cleanup()
        for node in nodes:
            node.destroy_node()
        rclpy.try_shutdown()
