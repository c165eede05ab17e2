"""ExecuteProcess: run a command, prefix its output lines, stop it with SIGINT -> SIGTERM -> SIGKILL."""

from __future__ import annotations

import asyncio
import codecs
import itertools
import os
import re
import shlex
import signal
import subprocess
import traceback
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from launch.action import Action
from launch.actions.shutdown_action import Shutdown
from launch.descriptions.executable import Executable
from launch.event_handler import CallbackEventHandler, reaction_callable
from launch.events.process.process_exited import ProcessExited
from launch.events.process.process_started import ProcessStarted
from launch.events.process.process_stderr import ProcessStderr
from launch.events.process.process_stdout import ProcessStdout
from launch.events.process.shutdown_process import ShutdownProcess
from launch.events.process.signal_process import SignalProcess
from launch.events.shutdown import Shutdown as ShutdownEvent
from launch.frontend.expose import expose_action
from launch.logging import get_logger, write_process_line
from launch.some_substitutions_type import SomeSubstitutionsType
from launch.substitution import Substitution, describe_substitutions
from launch.substitutions.launch_configuration import LaunchConfiguration
from launch.substitutions.text_substitution import TextSubstitution
from launch.utilities.normalize_to_list_of_substitutions_impl import normalize_to_list_of_substitutions
from launch.utilities.perform_substitutions_impl import perform_substitutions
from launch.utilities.type_utils import perform_typed_substitution

if TYPE_CHECKING:
    from launch.event import Event
    from launch.frontend import Entity, Parser
    from launch.launch_context import LaunchContext

# Every prepared process gets the next number: labels are <name>-1, <name>-2, ...
_process_numbers = itertools.count(1)

OUTPUT_ALIASES: dict[str, dict[str, set[str]]] = {
    'screen': {'stdout': {'screen'}, 'stderr': {'screen'}},
    'log': {'stdout': {'log'}, 'stderr': {'log', 'screen'}},
    'both': {'stdout': {'screen', 'log'}, 'stderr': {'screen', 'log'}},
    'own_log': {'stdout': {'own_log'}, 'stderr': {'own_log'}},
    'full': {'stdout': {'screen', 'log', 'own_log'}, 'stderr': {'screen', 'log', 'own_log'}},
}
# Both overridable per launch: `ros2 launch ... sigterm_timeout:=15`.
DEFAULT_SIGTERM_TIMEOUT = LaunchConfiguration('sigterm_timeout', default=5)
DEFAULT_SIGKILL_TIMEOUT = LaunchConfiguration('sigkill_timeout', default=5)
# Seconds a child's output pipes may stay open after it exited (a grandchild may hold them).
OUTPUT_DRAIN_TIMEOUT = 1.0


def output_destinations(output: str | dict[str, str]) -> dict[str, set[str]]:
    """Where stdout and stderr lines go for an `output` setting (alias or per-stream dict)."""
    if isinstance(output, str):
        if output not in OUTPUT_ALIASES:
            raise ValueError(f'{output} is not a valid standard output config i.e. "screen", "log" or "both"')
        return OUTPUT_ALIASES[output]
    result: dict[str, set[str]] = {'stdout': set(), 'stderr': set()}
    for key, value in output.items():
        if key not in ('stdout', 'stderr', 'both') or value not in ('screen', 'log', 'own_log', 'both'):
            raise ValueError(f'{output} is not a valid standard output config i.e. "screen", "log" or "both"')
        targets = {'screen', 'log'} if value == 'both' else {value}
        for stream in (('stdout', 'stderr') if key == 'both' else (key,)):
            result[stream] |= targets
    return result


def _substitutions_or_value(value: Any) -> Any:
    """bool/number/dict settings stay as they are; text becomes substitutions."""
    if value is None or isinstance(value, (bool, int, float, dict)):
        return value
    return normalize_to_list_of_substitutions(value)


class _OutputStream:
    """Turns chunks of one output stream into complete lines (a partial line waits)."""

    def __init__(self, action: ExecuteProcess, stream: str, destinations: set[str]) -> None:
        self.action = action
        self.stream = stream
        self.destinations = destinations
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
        write_process_line(text, self.action.process_description.final_name or '', self.stream,
                           self.destinations)


@expose_action('executable')
class ExecuteProcess(Action):
    """Run one process; see the module docstring for the stop sequence."""

    def __init__(
            self, *, cmd: Iterable[SomeSubstitutionsType], prefix: SomeSubstitutionsType | None = None,
            name: SomeSubstitutionsType | None = None, cwd: SomeSubstitutionsType | None = None,
            env: dict[SomeSubstitutionsType, SomeSubstitutionsType] | None = None,
            additional_env: dict[SomeSubstitutionsType, SomeSubstitutionsType] | None = None,
            shell: bool = False,
            sigterm_timeout: SomeSubstitutionsType = DEFAULT_SIGTERM_TIMEOUT,
            sigkill_timeout: SomeSubstitutionsType = DEFAULT_SIGKILL_TIMEOUT,
            emulate_tty: bool | SomeSubstitutionsType = False,
            output: SomeSubstitutionsType | dict[str, str] = 'log',
            output_format: str = '[{this.process_description.final_name}] {line}',
            log_cmd: bool = False, on_exit: Any = None,
            respawn: bool | SomeSubstitutionsType = False,
            respawn_delay: float | None = None, respawn_max_retries: int = -1,
            **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.cmd = [normalize_to_list_of_substitutions(item) for item in cmd]
        self.prefix = None if prefix is None else normalize_to_list_of_substitutions(prefix)
        self.name = None if name is None else normalize_to_list_of_substitutions(name)
        self.cwd = None if cwd is None else normalize_to_list_of_substitutions(cwd)
        self.env = None if env is None else self._pairs(env)
        self.additional_env = [] if additional_env is None else self._pairs(additional_env)
        self.shell = shell
        self.sigterm_timeout = normalize_to_list_of_substitutions(sigterm_timeout)
        self.sigkill_timeout = normalize_to_list_of_substitutions(sigkill_timeout)
        self.emulate_tty = _substitutions_or_value(emulate_tty)
        override = os.environ.get('OVERRIDE_LAUNCH_PROCESS_OUTPUT')
        self.output = _substitutions_or_value(override or output)
        if isinstance(self.output, dict):
            output_destinations(self.output)  # a bad dict is an error now, not at launch time
        self.output_format = output_format
        self.log_cmd = log_cmd
        self.on_exit = on_exit
        self.respawn = _substitutions_or_value(respawn)
        self.respawn_delay = respawn_delay
        self.respawn_max_retries = respawn_max_retries
        self.process_description = Executable()
        self._executed = False
        self._process: asyncio.subprocess.Process | None = None
        self._future: asyncio.Future | None = None
        self._shutdown_started = False
        self._shutdown_sends_sigint = True
        self._stop_requested: asyncio.Event | None = None
        self._timers: list[asyncio.TimerHandle] = []
        self._return_code: int | None = None
        self._task: asyncio.Task | None = None

    @staticmethod
    def _pairs(mapping: Any) -> list[tuple[list[Substitution], list[Substitution]]]:
        items = mapping.items() if isinstance(mapping, dict) else mapping
        return [(normalize_to_list_of_substitutions(k), normalize_to_list_of_substitutions(v))
                for k, v in items]

    # ---- frontend ----
    @classmethod
    def _parse_process_attributes(cls, entity: Entity, parser: Parser) -> dict[str, Any]:
        """The attributes <executable> and <node> share."""
        kwargs: dict[str, Any] = {}
        for attribute, keyword in (('cwd', 'cwd'), ('name', 'name'), ('launch-prefix', 'prefix'),
                                   ('output', 'output'), ('respawn', 'respawn'),
                                   ('emulate_tty', 'emulate_tty'),
                                   ('sigterm_timeout', 'sigterm_timeout'),
                                   ('sigkill_timeout', 'sigkill_timeout')):
            value = entity.get_attr(attribute, optional=True)
            if value is not None:
                kwargs[keyword] = parser.substitutions(value)
        shell = parser.boolean(entity, 'shell')
        if shell is not None:
            kwargs['shell'] = shell
        for attribute, convert in (('respawn_delay', float), ('respawn_max_retries', int)):
            value = entity.get_attr(attribute, optional=True)
            if value is not None:
                try:
                    kwargs[attribute] = convert(value)
                except (TypeError, ValueError):
                    raise entity.error(f"attribute '{attribute}' must be a number, got {value!r}") from None
        on_exit = entity.get_attr('on_exit', optional=True)
        if on_exit is not None:
            if on_exit != 'shutdown':
                raise entity.error(f"on_exit only supports 'shutdown', got {on_exit!r}")
            kwargs['on_exit'] = [Shutdown()]
        env = entity.get_children('env')
        if env:
            kwargs['additional_env'] = [(parser.substitutions(e.get_attr('name')),
                                         parser.substitutions(e.get_attr('value'))) for e in env]
            for e in env:
                e.assert_entity_completely_parsed()
        return kwargs

    @classmethod
    def parse(cls, entity: Entity, parser: Parser) -> tuple[type, dict[str, Any]]:
        kwargs = cls._parse_process_attributes(entity, parser)
        kwargs['cmd'] = split_command_line(parser.substitutions(entity.get_attr('cmd')))
        return cls, kwargs

    # ---- description ----
    def describe(self) -> str:
        return 'ExecuteProcess(cmd=[' + ', '.join(describe_substitutions(c) for c in self.cmd) + '])'

    def get_asyncio_future(self) -> asyncio.Future | None:
        return self._future

    @property
    def return_code(self) -> int | None:
        return self._return_code

    def _extra_arguments(self, context: LaunchContext) -> list[str]:
        """Arguments appended after cmd (Node adds its --ros-args here)."""
        return []

    def _prepare(self, context: LaunchContext) -> None:
        cmd = [perform_substitutions(context, item) for item in self.cmd]
        cmd += self._extra_arguments(context)
        if self.prefix is not None:
            prefix = perform_substitutions(context, self.prefix)
        else:
            prefix = str(context.launch_configurations.get('launch-prefix', ''))
            prefix_filter = str(context.launch_configurations.get('launch-prefix-filter', ''))
            if prefix_filter and not re.match(prefix_filter, os.path.basename(cmd[0])):
                prefix = ''
        final_cmd = shlex.split(prefix) + cmd
        name = (perform_substitutions(context, self.name) if self.name is not None
                else os.path.basename(final_cmd[0]))
        if self.env is not None:
            env = {perform_substitutions(context, k): perform_substitutions(context, v)
                   for k, v in self.env}
        else:
            env = dict(context.environment)
        for key, value in self.additional_env:
            env[perform_substitutions(context, key)] = perform_substitutions(context, value)
        description = self.process_description
        description.final_cmd = final_cmd
        description.final_name = f'{name}-{next(_process_numbers)}'
        description.final_cwd = None if self.cwd is None else perform_substitutions(context, self.cwd)
        description.final_env = env

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
        output = self.output
        if isinstance(output, list):
            output = perform_substitutions(context, output)
        self._destinations = output_destinations(output)
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
        return describe_substitutions(self.name if self.name is not None else self.cmd[0])

    def _event_fields(self, pid: int) -> dict[str, Any]:
        description = self.process_description
        return {'action': self, 'name': description.final_name, 'cmd': description.final_cmd,
                'cwd': description.final_cwd, 'env': description.final_env, 'pid': pid}

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
                              f"cwd='{description.final_cwd}', custom_env?={self.env is not None}")
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
        context.emit_event_sync(ProcessStarted(**self._event_fields(pid)))
        if self._shutdown_started:  # shutdown came while the process was being spawned
            self._begin_termination(context, self._shutdown_sends_sigint)
        streams = [self._relay(context, out_read, _OutputStream(self, 'stdout', self._destinations['stdout']),
                               ProcessStdout, pid),
                   self._relay(context, err_read, _OutputStream(self, 'stderr', self._destinations['stderr']),
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


def split_command_line(substitutions: list[Substitution]) -> list[list[Substitution]]:
    """Split a frontend `cmd` into argv items with shell quoting rules applied to its literal text.

    Substitutions (also inside quotes) stay where they are, each a placeholder while splitting, so
    a substitution glued to text is in the same item and its own value is never split.
    """
    placeholders: dict[str, Substitution] = {}
    text = []
    for sub in substitutions:
        if isinstance(sub, TextSubstitution):
            text.append(sub.text)
        else:
            marker = f'\0{len(placeholders)}\0'
            placeholders[marker] = sub
            text.append(marker)
    try:
        tokens = shlex.split(''.join(text))
    except ValueError as error:  # e.g. an unclosed quote
        raise ValueError(f"cannot split command line '{''.join(text)}': {error}") from None
    items = []
    for token in tokens:
        item: list[Substitution] = []
        for piece in re.split('(\0\\d+\0)', token):
            if piece in placeholders:
                item.append(placeholders[piece])
            elif piece:
                item.append(TextSubstitution(text=piece))
        items.append(item or [TextSubstitution(text='')])
    return items
