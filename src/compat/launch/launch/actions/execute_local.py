"""ExecuteLocal: run an Executable as a local process; stop it with SIGINT -> SIGTERM -> SIGKILL."""

from __future__ import annotations

import asyncio
import codecs
import logging
import os
import signal
import subprocess
import traceback
from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.descriptions.executable import Executable
from launch.event_handler import CallbackEventHandler, reaction_callable
from launch.events.process.process_exited import ProcessExited
from launch.events.process.process_started import ProcessStarted
from launch.events.process.process_stderr import ProcessStderr
from launch.events.process.process_stdout import ProcessStdout
from launch.events.process.shutdown_process import ShutdownProcess
from launch.events.process.signal_process import SignalProcess
from launch.events.shutdown import Shutdown as ShutdownEvent
from launch.launch_description_entity import LaunchDescriptionEntity
from launch.logging import get_logger, get_output_loggers, normalize_output_config
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import describe_substitutions
from launch.substitutions.launch_configuration import LaunchConfiguration
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions
from launch.utilities.type_utils import perform_typed_substitution

if TYPE_CHECKING:
    from launch.event import Event
    from launch.launch_context import LaunchContext

# Both overridable per launch: `ros2 launch ... sigterm_timeout:=15`.
DEFAULT_SIGTERM_TIMEOUT = LaunchConfiguration('sigterm_timeout', default=5)
DEFAULT_SIGKILL_TIMEOUT = LaunchConfiguration('sigkill_timeout', default=5)
# Seconds a child's output pipes may stay open after it exited (a grandchild may hold them).
OUTPUT_DRAIN_TIMEOUT = 1.0


def _substitutions_or_value(value: Any) -> Any:
    """bool/number/dict settings stay as they are; text becomes substitutions."""
    if value is None or isinstance(value, (bool, int, float, dict)):
        return value
    return normalize_to_list_of_substitutions(value)


class _OutputStream:
    """Turns chunks of one output stream into complete lines (a partial line waits)."""

    def __init__(self, action: ExecuteLocal, stream: str, logger: logging.Logger) -> None:
        self.action = action
        self.stream = stream
        self.logger = logger
        self.decoder = codecs.getincrementaldecoder('utf-8')(errors='replace')
        self.pending = ''

    def feed(self, data: bytes) -> None:
        self.pending += self.decoder.decode(data)
        *lines, self.pending = self.pending.split('\n')
        for line in lines:
            self._write(line)

    def flush(self) -> None:
        self.pending += self.decoder.decode(b'', final=True)
        if self.pending:
            self._write(self.pending)
            self.pending = ''

    def _write(self, line: str) -> None:
        line = line.rstrip('\r')  # a pty ends lines with \r\n
        text = self.action.output_format.format(line=line, this=self.action)
        if self.action.cached_output:
            self.action._cache(self.stream).append(line)
        self.logger.info(text)


class ExecuteLocal(Action):
    """Run one process_description; see the module docstring for the stop sequence.

    process_details is None until executed, then the dict of fields its process events carry:
    action, name, cmd, cwd, env, and pid once the process has started (the latest one's on respawn).
    """

    def __init__(
            self, *, process_description: Executable, shell: bool = False,
            sigterm_timeout: SomeSubstitutionsType = DEFAULT_SIGTERM_TIMEOUT,
            sigkill_timeout: SomeSubstitutionsType = DEFAULT_SIGKILL_TIMEOUT,
            emulate_tty: bool | SomeSubstitutionsType = False,
            output: SomeSubstitutionsType | dict[str, str] = 'log',
            output_format: str = '[{this.process_description.final_name}] {line}',
            cached_output: bool = False, log_cmd: bool = False, on_exit: Any = None,
            respawn: bool | SomeSubstitutionsType = False,
            respawn_delay: float | None = None, respawn_max_retries: int = -1,
            **kwargs: Any) -> None:
        super().__init__(**kwargs)
        if not isinstance(process_description, Executable):
            raise TypeError("ExecuteLocal 'process_description' must be a launch.descriptions.Executable, "
                            f"got '{type(process_description).__name__}'")
        self.process_description = process_description
        self.shell = shell
        self.sigterm_timeout = normalize_to_list_of_substitutions(sigterm_timeout)
        self.sigkill_timeout = normalize_to_list_of_substitutions(sigkill_timeout)
        self.emulate_tty = _substitutions_or_value(emulate_tty)
        override = os.environ.get('OVERRIDE_LAUNCH_PROCESS_OUTPUT')
        self.output = _substitutions_or_value(override or output)
        if isinstance(self.output, dict):
            normalize_output_config(self.output)  # a bad dict is an error now, not at launch time
        self.output_format = output_format
        self.cached_output = cached_output
        self.log_cmd = log_cmd
        self.on_exit = on_exit
        self.respawn = _substitutions_or_value(respawn)
        self.respawn_delay = respawn_delay
        self.respawn_max_retries = respawn_max_retries
        self._stdout_cache: list[str] = []
        self._stderr_cache: list[str] = []
        self._process_details: dict[str, Any] | None = None
        self._executed = False
        self._process: asyncio.subprocess.Process | None = None
        self._future: asyncio.Future | None = None
        self._shutdown_started = False
        self._shutdown_sends_sigint = True
        self._stop_requested: asyncio.Event | None = None
        self._timers: list[asyncio.TimerHandle] = []
        self._return_code: int | None = None
        self._task: asyncio.Task | None = None

    @property
    def process_details(self) -> dict[str, Any] | None:
        return self._process_details

    def get_stdout(self) -> str:
        """The output lines so far (cached_output=True only), each ending in a newline."""
        return self._cached_text('stdout')

    def get_stderr(self) -> str:
        """As get_stdout, for stderr."""
        return self._cached_text('stderr')

    def _cache(self, stream: str) -> list[str]:
        return self._stdout_cache if stream == 'stdout' else self._stderr_cache

    def _cached_text(self, stream: str) -> str:
        if not self.cached_output:
            raise RuntimeError(f'get_{stream}() needs the action to be created with cached_output=True')
        return ''.join(line + '\n' for line in self._cache(stream))

    def get_sub_entities(self) -> list[LaunchDescriptionEntity]:
        """The on_exit actions, when given as a list (a callable has none to show)."""
        return list(self.on_exit) if isinstance(self.on_exit, list) else []

    # ---- description ----
    def describe(self) -> str:
        cmd = self.process_description.cmd
        return f'{type(self).__name__}(cmd=[' + ', '.join(describe_substitutions(c) for c in cmd) + '])'

    def get_asyncio_future(self) -> asyncio.Future | None:
        return self._future

    @property
    def return_code(self) -> int | None:
        return self._return_code

    def _extra_arguments(self, context: LaunchContext) -> list[str]:
        """Arguments appended after cmd (Node adds its --ros-args here)."""
        return []

    def _prepare(self, context: LaunchContext) -> None:
        description = self.process_description
        description.prepare(context, self)
        assert description.final_cmd is not None
        description.final_cmd = description.final_cmd + self._extra_arguments(context)

    def _flag(self, context: LaunchContext, value: Any) -> bool:
        """A bool setting (respawn, emulate_tty) given as a bool or as text read the YAML way."""
        if value is None or isinstance(value, bool):
            return bool(value)
        return perform_typed_substitution(context, value, bool)

    # ---- execution ----
    def execute(self, context: LaunchContext) -> None:
        if self._executed:
            raise RuntimeError(f"ExecuteLocal action '{self.name_for_errors}': executed more than once: "
                               f'{self.describe()}')
        self._executed = True
        if context.is_shutdown:
            return None
        self._prepare(context)
        description = self.process_description
        # The process events' fields; 'pid' joins once the process has started.
        self._process_details = {'action': self, 'name': description.final_name, 'cmd': description.final_cmd,
                                 'cwd': description.final_cwd, 'env': description.final_env}
        output = self.output
        if isinstance(output, list):
            output = perform_substitutions(context, output)
        self._output_loggers = get_output_loggers(self.process_description.final_name or 'process', output)
        tty_setting = context.launch_configurations.get('emulate_tty')
        self._use_tty = self._flag(context, self.emulate_tty if tty_setting is None
                                   else normalize_to_list_of_substitutions(tty_setting))
        self._logger = get_logger(self.process_description.final_name or 'process')
        context.register_event_handler(CallbackEventHandler(
            matcher=lambda event: isinstance(event, ShutdownEvent), callback=self._on_shutdown))
        context.register_event_handler(CallbackEventHandler(
            matcher=lambda event: isinstance(event, ShutdownProcess) and event.process_matcher(self),
            callback=lambda _event, ctx: self._stop(ctx, send_sigint=True)))
        context.register_event_handler(CallbackEventHandler(
            matcher=lambda event: isinstance(event, SignalProcess) and event.process_matcher(self),
            callback=lambda event, _ctx: self._send_signal(event.signal)))  # type: ignore[attr-defined]
        if self.on_exit is not None:
            context.register_event_handler(CallbackEventHandler(
                matcher=lambda event: isinstance(event, ProcessExited) and event.action is self,
                callback=reaction_callable(self.on_exit)))
        context._process_actions.append(self)
        loop = asyncio.get_running_loop()
        self._future = loop.create_future()
        self._stop_requested = asyncio.Event()
        self._task = loop.create_task(self._run(context))
        return None

    @property
    def name_for_errors(self) -> str:
        if self.process_description.final_name:
            return self.process_description.final_name
        description = self.process_description
        return describe_substitutions(description.name or description.cmd[0])

    def _event_fields(self, pid: int) -> dict[str, Any]:
        assert self._process_details is not None  # set by execute
        return {**self._process_details, 'pid': pid}

    async def _run(self, context: LaunchContext) -> None:
        retries = 0
        try:
            while await self._run_once(context):
                if not self._flag(context, self.respawn) or context.is_shutdown or self._shutdown_started:
                    break
                if 0 <= self.respawn_max_retries <= retries:
                    break
                retries += 1
                if self.respawn_delay:
                    assert self._stop_requested is not None
                    try:
                        await asyncio.wait_for(self._stop_requested.wait(), self.respawn_delay)
                    except asyncio.TimeoutError:
                        pass
                if context.is_shutdown or self._shutdown_started:
                    break
        except Exception as error:
            if self._future is not None and not self._future.done():
                self._future.set_exception(error)
        finally:
            self._cancel_timers()
            if self._future is not None and not self._future.done():
                self._future.set_result(None)

    def _open_output(self) -> tuple[tuple[int, int], tuple[int, int]]:
        """(read, write) descriptor pairs for stdout and stderr: ptys or pipes."""
        if self._use_tty:
            return os.openpty(), os.openpty()
        return os.pipe(), os.pipe()

    async def _run_once(self, context: LaunchContext) -> bool:
        """Start the process, relay its output until it exits; False if it could not start."""
        description = self.process_description
        assert description.final_cmd is not None
        if self.log_cmd:
            self._logger.info(f"process details: cmd='{' '.join(description.final_cmd)}', "
                              f"cwd='{description.final_cwd}', custom_env?={description.env is not None}")
        (out_read, out_write), (err_read, err_write) = self._open_output()
        try:
            options: dict[str, Any] = {
                'stdin': subprocess.PIPE, 'stdout': out_write, 'stderr': err_write,
                'env': description.final_env, 'cwd': description.final_cwd}
            if self.shell:
                process = await asyncio.create_subprocess_shell(
                    ' '.join(description.final_cmd), **options)
            else:
                process = await asyncio.create_subprocess_exec(*description.final_cmd, **options)
        except Exception as error:
            for fd in (out_read, err_read):
                os.close(fd)
            # Upstream prints the whole traceback here; the error line says all a user can act on.
            self._logger.error('exception occurred while executing process:\n'
                               f'{type(error).__name__}: {error}')
            self._logger.debug(traceback.format_exc())
            return False
        finally:
            os.close(out_write)
            os.close(err_write)
        self._process = process
        pid = process.pid
        self._logger.info(f'process started with pid [{pid}]')
        self._process_details = self._event_fields(pid)
        context.emit_event_sync(ProcessStarted(**self._event_fields(pid)))
        if self._shutdown_started:  # shutdown came while the process was being spawned
            self._begin_termination(context, self._shutdown_sends_sigint)
        streams = [self._relay(context, out_read, _OutputStream(self, 'stdout', self._output_loggers[0]),
                               ProcessStdout, pid),
                   self._relay(context, err_read, _OutputStream(self, 'stderr', self._output_loggers[1]),
                               ProcessStderr, pid)]
        relays = [asyncio.ensure_future(s) for s in streams]
        return_code = await process.wait()
        await asyncio.wait(relays, timeout=OUTPUT_DRAIN_TIMEOUT)
        for relay in relays:
            relay.cancel()
        await asyncio.gather(*relays, return_exceptions=True)
        if process.stdin is not None:
            process.stdin.close()
        self._process = None
        self._return_code = return_code
        self._cancel_timers()
        if return_code == 0:
            self._logger.info(f'process has finished cleanly [pid {pid}]')
        else:
            self._logger.error(f'process has died [pid {pid}, exit code {return_code}, '
                               f"cmd '{' '.join(description.final_cmd)}'].")
        context.emit_event_sync(ProcessExited(returncode=return_code, **self._event_fields(pid)))
        return True

    async def _relay(self, context: LaunchContext, fd: int, stream: _OutputStream,
                     event_type: type, pid: int) -> None:
        """Read fd until end of file, writing lines and emitting IO events; always closes fd."""
        loop = asyncio.get_running_loop()
        done = loop.create_future()
        os.set_blocking(fd, False)

        def readable() -> None:
            try:
                data = os.read(fd, 65536)
            except BlockingIOError:
                return
            except OSError:  # EIO: the pty's other side closed
                data = b''
            if not data:
                if not done.done():
                    done.set_result(None)
                return
            stream.feed(data)
            event = event_type(text=data, **self._event_fields(pid))
            if context.would_handle_event(event):
                context.emit_event_sync(event)

        loop.add_reader(fd, readable)
        try:
            await done
        finally:
            loop.remove_reader(fd)
            os.close(fd)
            stream.flush()

    # ---- stopping ----
    def _on_shutdown(self, event: Event, context: LaunchContext) -> None:
        # An interactive Ctrl-C already reached the whole process group: do not send it twice.
        due_to_sigint = getattr(event, 'due_to_sigint', False)
        self._stop(context, send_sigint=not due_to_sigint or context.noninteractive)

    def _stop(self, context: LaunchContext, send_sigint: bool) -> None:
        if self._shutdown_started:
            return
        self._shutdown_started = True
        self._shutdown_sends_sigint = send_sigint
        if self._stop_requested is not None:
            self._stop_requested.set()
        if self._process is not None and self._process.returncode is None:
            self._begin_termination(context, send_sigint)

    def _begin_termination(self, context: LaunchContext, send_sigint: bool) -> None:
        """SIGINT now (maybe), SIGTERM after sigterm_timeout, SIGKILL after both timeouts."""
        sigterm_text = perform_substitutions(context, self.sigterm_timeout)
        sigkill_text = perform_substitutions(context, self.sigkill_timeout)
        try:
            term_after = float(sigterm_text)
            kill_after = term_after + float(sigkill_text)
        except ValueError:
            raise ValueError(f"sigterm_timeout and sigkill_timeout must be numbers of seconds, got "
                             f"'{sigterm_text}' and '{sigkill_text}'") from None
        loop = asyncio.get_running_loop()
        self._timers = [
            loop.call_later(term_after, self._escalate, 'SIGINT', 'SIGTERM', sigterm_text),
            loop.call_later(kill_after, self._escalate, 'SIGTERM', 'SIGKILL', str(kill_after)),
        ]
        if send_sigint:
            self._send_signal(signal.SIGINT)

    def _escalate(self, previous: str, following: str, after: str) -> None:
        if self._process is None or self._process.returncode is not None:
            return
        label = self.process_description.final_name
        self._logger.error(f"process[{label}] failed to terminate '{after}' seconds after receiving "
                           f"'{previous}', escalating to '{following}'")
        self._send_signal(getattr(signal, following))

    def _send_signal(self, signal_number: int) -> None:
        process = self._process
        if process is None or process.returncode is not None:
            return
        label = self.process_description.final_name
        self._logger.info(f"sending signal '{signal.Signals(signal_number).name}' to process[{label}]")
        # os.kill, not process.send_signal: Popen.send_signal first polls, and that poll would reap
        # a child that has just died, leaving asyncio's watcher with an "unknown" pid (code 255).
        # The pid cannot be reused before the watcher reaps it, so signalling it here is safe.
        try:
            os.kill(process.pid, signal_number)
        except ProcessLookupError:
            pass

    def _cancel_timers(self) -> None:
        for timer in self._timers:
            timer.cancel()
        self._timers = []

    def kill_if_running(self) -> int | None:
        """Last resort when launch itself is cancelled: SIGKILL a still-running process."""
        process = self._process
        if process is None or process.returncode is not None:
            return None
        try:
            os.kill(process.pid, signal.SIGKILL)
        except ProcessLookupError:
            return None
        return process.pid
