"""LaunchService: the asyncio event loop that visits entities, dispatches events and shuts down."""

from __future__ import annotations

import asyncio
import logging
import os
import select
import signal
import threading
import traceback
from collections.abc import Coroutine, Iterable
from typing import Any

import launch.logging
from launch.event import Event
from launch.event_handler import CallbackEventHandler
from launch.event_handlers.on_include_launch_description import OnIncludeLaunchDescription
from launch.events.include_launch_description import IncludeLaunchDescription as IncludeLaunchDescriptionEvent
from launch.events.shutdown import Shutdown
from launch.launch_context import LaunchContext
from launch.launch_description import LaunchDescription
from launch.launch_description_entity import LaunchDescriptionEntity
from launch.utilities.signal_management import AsyncSafeSignalManager
from launch.utilities.visit_all_entities_and_collect_futures_impl import visit_entities_into

KILLED_EXIT_TIMEOUT = 5.0  # s a SIGKILLed process gets to end before launch exits anyway


async def _shutdown_queued() -> None:
    """What LaunchService.shutdown() gives inside the loop: the event is already queued."""


class LaunchService:
    """Runs launch descriptions until everything has shut down; run() returns the exit code.

    0 after an idle shutdown, a Shutdown action or Ctrl-C (whatever the children's exit codes);
    1 if an exception was caught in launch or launch itself got SIGTERM/SIGQUIT.
    """

    def __init__(self, *, argv: Iterable[str] | None = None, noninteractive: bool = False,
                 debug: bool = False) -> None:
        self.__debug = debug
        launch.logging.launch_config.level = logging.DEBUG if debug else logging.INFO
        launch.logging.setup_log_dir()
        self.__logger = launch.logging.get_logger('launch')
        launch.logging.log_launch_config(self.__logger)
        self.__context = LaunchContext(argv=argv, noninteractive=noninteractive)
        self.__context.register_event_handler(OnIncludeLaunchDescription())
        self.__context.register_event_handler(CallbackEventHandler(
            matcher=lambda event: isinstance(event, Shutdown), callback=self._on_shutdown))
        self.__futures: list[tuple[LaunchDescriptionEntity, asyncio.Future]] = []
        self.__return_code = 0
        self.__loop: asyncio.AbstractEventLoop | None = None
        self.__sigint_count = 0

    @property
    def context(self) -> LaunchContext:
        return self.__context

    def include_launch_description(self, launch_description: LaunchDescription) -> None:
        self.__context.emit_event_sync(IncludeLaunchDescriptionEvent(launch_description))

    def _on_shutdown(self, event: Event, context: LaunchContext) -> None:
        context._is_shutdown = True

    def shutdown(self, force_sync: bool = False) -> Coroutine[Any, Any, None] | None:
        """Shut a running launch down; does nothing when it is not running.  Thread-safe.

        Inside the launch's own loop it returns a coroutine, as upstream, so callers can await it or
        make a task of it; the Shutdown event is queued at once, so one that is never awaited (Python
        warns) still shuts down. force_sync queues the event directly instead of through the loop.
        """
        loop = self.__loop
        if loop is None or not loop.is_running():
            return None
        event = Shutdown(reason='LaunchService.shutdown() called')
        if force_sync:
            self.__context.emit_event_sync(event)
            return None
        try:
            in_loop = asyncio.get_running_loop() is loop
        except RuntimeError:  # no loop runs in this thread
            in_loop = False
        if not in_loop:
            loop.call_soon_threadsafe(self.__context.emit_event_sync, event)
            return None
        self.__context.emit_event_sync(event)
        return _shutdown_queued()

    def run(self, *, shutdown_when_idle: bool = True) -> int:
        if threading.current_thread() is not threading.main_thread():
            raise RuntimeError('LaunchService can only be run in the main thread.')
        loop = asyncio.new_event_loop()
        loop.set_debug(self.__debug)
        try:
            return loop.run_until_complete(self.run_async(shutdown_when_idle=shutdown_when_idle))
        finally:
            pending = [task for task in asyncio.all_tasks(loop) if not task.done()]
            for task in pending:
                task.cancel()
            if pending:
                loop.run_until_complete(asyncio.gather(*pending, return_exceptions=True))
            loop.run_until_complete(loop.shutdown_asyncgens())
            loop.close()
            launch.logging.close_process_logs()

    async def run_async(self, *, shutdown_when_idle: bool = True) -> int:
        loop = asyncio.get_running_loop()
        self.__loop = loop
        context = self.__context
        context._asyncio_loop = loop
        context._wakeup = asyncio.Event()
        context._wakeup.set()
        main_task = asyncio.current_task()
        assert main_task is not None
        loop.set_exception_handler(self._on_asyncio_exception)
        with AsyncSafeSignalManager(loop) as signals:
            self._install_signal_handlers(signals, main_task)
            try:
                await self._process_events(shutdown_when_idle)
            except asyncio.CancelledError:
                self.__logger.error('run task was canceled')
                self.__return_code = 1
                self._kill_leftover_processes()
            finally:
                self.__loop = None
        return self.__return_code

    def _install_signal_handlers(self, signals: AsyncSafeSignalManager, main_task: asyncio.Task) -> None:
        def on_sigint(_signum: int) -> None:
            self.__sigint_count += 1
            if self.__sigint_count > 1:
                self.__logger.warning('user interrupted with ctrl-c (SIGINT) again, ignoring...')
                return
            self.__logger.warning('user interrupted with ctrl-c (SIGINT)')
            self.__context.emit_event_sync(Shutdown(reason='ctrl-c (SIGINT)', due_to_sigint=True))

        def on_terminate(signum: int) -> None:
            name = signal.Signals(signum).name
            self.__logger.error(f'user interrupted with ctrl-\\ ({name}), terminating...')
            self.__logger.error(f'using {name} can result in orphaned processes')
            self.__logger.error('make sure no processes launched are still running')
            main_task.cancel()

        for signum, handler in ((signal.SIGINT, on_sigint), (signal.SIGTERM, on_terminate),
                                (signal.SIGQUIT, on_terminate)):
            try:
                signals.handle(signum, handler)
            except ValueError:  # not the main thread of the main interpreter
                pass

    def _on_asyncio_exception(self, loop: asyncio.AbstractEventLoop, details: dict[str, Any]) -> None:
        self._report(details.get('exception') or RuntimeError(details.get('message', 'asyncio error')))

    def _report(self, error: BaseException) -> None:
        """An exception in launch: log it, return 1 at the end, and shut down."""
        message = str(error)
        try:
            path = self.__context.locals.current_launch_file_path
        except AttributeError:
            path = None
        if path and path not in message:
            message += f' (launch file: {path})'
        self.__logger.error(f'Caught exception in launch (see debug for traceback): {message}')
        self.__logger.debug(''.join(traceback.format_exception(error)))
        self.__return_code = 1
        if not self.__context.is_shutdown:
            self.__context.emit_event_sync(Shutdown(reason=str(error)))

    def _visit(self, entity: LaunchDescriptionEntity) -> None:
        """Visit an entity and, depth first and in order, whatever it yields."""
        visit_entities_into(entity, self.__context, self.__futures)

    def _handle(self, event: Event) -> None:
        context = self.__context
        # Handlers registered while this event is handled do not see it.
        for handler in [h for h in context._event_handlers if h.matches(event)]:
            depth = (len(context._locals_frames), len(context._configurations_stack),
                     len(context._environment_stack))
            context._push_locals()
            try:
                entities = handler.handle(event, context)
                if isinstance(entities, LaunchDescriptionEntity):
                    entities = [entities]
                for entity in entities or []:
                    self._visit(entity)
            except Exception as error:
                self._report(error)
            finally:
                # An exception may leave scopes of groups and includes open: close them.
                del context._locals_frames[depth[0]:]
                while len(context._configurations_stack) > depth[1]:
                    context._pop_launch_configurations()
                while len(context._environment_stack) > depth[2]:
                    context._pop_environment()

    async def _process_events(self, shutdown_when_idle: bool) -> None:
        context = self.__context
        assert context._wakeup is not None
        while True:
            while context._event_queue:
                self._handle(context._event_queue.popleft())
            self._check_futures()
            if context._event_queue:
                continue
            pending = [future for _, future in self.__futures if not future.done()]
            pending += [future for future in context._completion_futures if not future.done()]
            if not pending:
                if context.is_shutdown:
                    return
                if shutdown_when_idle:
                    context.emit_event_sync(Shutdown(reason='idle'))
                    continue
            context._wakeup.clear()
            waiter = asyncio.ensure_future(context._wakeup.wait())
            await asyncio.wait([waiter, *pending], return_when=asyncio.FIRST_COMPLETED)
            waiter.cancel()

    def _check_futures(self) -> None:
        context = self.__context
        still_pending = []
        for entity, future in [*self.__futures, *((None, f) for f in context._completion_futures)]:
            if not future.done():
                still_pending.append((entity, future))
            elif not future.cancelled() and future.exception() is not None:
                self._report(future.exception())  # type: ignore[arg-type]
        self.__futures = [(entity, future) for entity, future in still_pending if entity is not None]
        context._completion_futures = [future for entity, future in still_pending if entity is None]

    def _kill_leftover_processes(self) -> None:
        """Launch was cancelled: SIGKILL what is still running rather than leave orphans.

        It returns once each has died: a SIGKILL takes effect when the process next runs, which on a
        busy machine came after launch had exited (the process then ran on, orphaned, for a moment).
        """
        killed = [pid for action in self.__context._process_actions
                  if (pid := action.kill_if_running()) is not None]
        for pid in killed:
            try:
                handle = os.pidfd_open(pid)  # readable once the process has ended; not reaped here
            except ProcessLookupError:
                continue
            try:
                select.select([handle], [], [], KILLED_EXIT_TIMEOUT)
            finally:
                os.close(handle)
