"""The rclpy node that launch itself uses (for lifecycle nodes), started on first use.

It has a context of its own, initialised without signal handlers (Ctrl-C belongs to launch's own
handler), and an executor spinning in a daemon thread.  Launch's shutdown stops it.
"""

from __future__ import annotations

import os
import threading
from typing import TYPE_CHECKING, Any

from launch.event_handlers import OnShutdown

if TYPE_CHECKING:
    from launch.event import Event
    from launch.launch_context import LaunchContext

__all__ = ['ROSAdapter', 'get_ros_adapter', 'get_ros_node']

# Seconds one spin of the adapter's executor may wait, so that a stop request is seen soon.
SPIN_PERIOD = 0.1


class ROSAdapter:
    """An rclpy context, a node `launch_ros_<pid>` in it and a thread spinning that node."""

    def __init__(self, *, argv: list[str] | None = None, autostart: bool = True) -> None:
        self.__argv = argv
        self.__node: Any = None
        self.__context: Any = None
        self.__executor: Any = None
        self.__thread: threading.Thread | None = None
        self.__stop = threading.Event()
        if autostart:
            self.start()

    def start(self) -> None:
        """Create the context and node, and start the thread spinning them.

        Raises RuntimeError if already started; SIGINT and SIGTERM are left to launch.
        """
        if self.__thread is not None:
            raise RuntimeError('ROSAdapter already started')
        # Lazy: rclpy takes long to import and only lifecycle nodes need it, while every launch
        # file with a ROS tag imports this package.
        import rclpy
        from rclpy.executors import SingleThreadedExecutor
        from rclpy.signals import SignalHandlerOptions

        self.__context = rclpy.Context()
        rclpy.init(args=self.__argv, context=self.__context,
                   signal_handler_options=SignalHandlerOptions.NO)
        self.__node = rclpy.create_node(f'launch_ros_{os.getpid()}', context=self.__context)
        self.__executor = SingleThreadedExecutor(context=self.__context)
        self.__executor.add_node(self.__node)
        self.__thread = threading.Thread(target=self._spin, name='launch_ros adapter', daemon=True)
        self.__thread.start()

    def _spin(self) -> None:
        while not self.__stop.is_set() and self.__context.ok():
            self.__executor.spin_once(timeout_sec=SPIN_PERIOD)

    def shutdown(self) -> None:
        """Stop the spinning thread, destroy the node and shut the context down; nothing if not started."""
        if self.__thread is None:
            return
        self.__stop.set()
        self.__thread.join()
        self.__thread = None
        self.__executor.shutdown()
        self.__node.destroy_node()
        self.__context.try_shutdown()

    @property
    def argv(self) -> list[str] | None:
        """The arguments rclpy is initialised with (None: none), as given to the constructor."""
        return self.__argv

    @property
    def ros_context(self) -> Any:
        """The adapter's own rclpy Context; None until started."""
        return self.__context

    @property
    def ros_node(self) -> Any:
        """The adapter's rclpy node (None until started), which lifecycle nodes' actions use."""
        return self.__node

    @property
    def ros_executor(self) -> Any:
        """The SingleThreadedExecutor that spins the node; None until started."""
        return self.__executor


def get_ros_adapter(context: LaunchContext) -> ROSAdapter:
    """The launch's ROSAdapter, created (and stopped at shutdown) on first use."""
    try:
        return context.locals.launch_ros_adapter
    except AttributeError:
        pass
    adapter = ROSAdapter()
    # Put in the outermost locals frame, so that every later action of this launch finds it.
    context._locals_frames[0]['launch_ros_adapter'] = adapter
    context._locals_frames[0]['launch_ros_node'] = adapter.ros_node

    def stop(_event: Event, _context: LaunchContext) -> None:
        adapter.shutdown()

    # Appended: processes get their SIGINT first, and the node stays until launch is done.
    context.register_event_handler(OnShutdown(on_shutdown=stop, handle_once=True), append=True)
    return adapter


def get_ros_node(context: LaunchContext) -> Any:
    """The rclpy node of the launch's ROSAdapter."""
    return get_ros_adapter(context).ros_node
