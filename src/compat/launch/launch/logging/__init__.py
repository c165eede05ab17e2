"""Launch's own output: `[LEVEL] [logger]: message` on the screen (stdout) and a launch.log on disk.

The loggers live in a logging tree of their own, so that launch's output neither reaches nor
depends on the Python root logger of the program that embeds launch. As upstream, each logger
holds its handlers itself and does not propagate: `launch_config` owns the one screen handler and
one handler per log file, and `get_logger` / `get_output_loggers` attach them.

Each LaunchService run gets a fresh log directory (`setup_log_dir`); outside a run,
`launch_config.log_dir` makes one on first use.
"""

from __future__ import annotations

import datetime
import logging
import os
import socket
import sys
import warnings
from collections.abc import Callable, Iterable
from pathlib import Path
from typing import Any, ClassVar, TextIO

from launch.logging import handlers

__all__ = ['get_logger', 'get_output_loggers', 'handlers', 'launch_config', 'reset']

SCREEN_FORMAT = '[{levelname}] [{name}]: {msg}'
LOG_FILE_FORMAT = '{created:.7f} [{levelname}] [{name}]: {msg}'
# A process's output lines are already `[label] line`: on the screen as they are, on disk with a timestamp.
PROCESS_SCREEN_FORMAT = '{msg}'
PROCESS_LOG_FILE_FORMAT = '{created:.7f} {msg}'
# Names set_screen_format / set_log_format (and the OVERRIDE_LAUNCH_*_FORMAT variables) take for a format.
SCREEN_FORMAT_ALIASES = {'default': SCREEN_FORMAT, 'default_with_timestamp': LOG_FILE_FORMAT}
LOG_FORMAT_ALIASES = {'default': LOG_FILE_FORMAT, 'default_with_timestamp': LOG_FILE_FORMAT}

# Where process output can go: the screen, launch.log, or files of the process's own.
OUTPUT_DESTINATIONS = ('screen', 'log', 'own_log')
OUTPUT_SOURCES = ('stdout', 'stderr', 'both')
# The `output` aliases, as destinations of each source ('both' is the combined <name>.log for own_log).
OUTPUT_ALIASES: dict[str, dict[str, set[str]]] = {
    'screen': {'both': {'screen'}},
    'log': {'both': {'log'}, 'stderr': {'screen'}},
    'both': {'both': {'screen', 'log'}},
    'own_log': {'both': {'own_log'}, 'stdout': {'own_log'}, 'stderr': {'own_log'}},
    'full': {'both': {'screen', 'log', 'own_log'}, 'stdout': {'own_log'}, 'stderr': {'own_log'}},
}

_process_screen_formatter = logging.Formatter(PROCESS_SCREEN_FORMAT, style='{')
_process_file_formatter = logging.Formatter(PROCESS_LOG_FILE_FORMAT, style='{')


class LaunchLogger(logging.Logger):
    """The loggers of launch's tree: they do not propagate, and reset() finds them all."""

    all_loggers: ClassVar[list[logging.Logger]] = []

    def __init__(self, name: str, level: int | str = logging.NOTSET) -> None:
        super().__init__(name, level)
        self.propagate = False
        LaunchLogger.all_loggers.append(self)


# The root only holds the level (launch_config.level) that every launch logger inherits.
_root = logging.RootLogger(logging.INFO)
_manager = logging.Manager(_root)
_root.manager = _manager  # else a level change would clear the level caches of Python's tree, not ours
_manager.setLoggerClass(LaunchLogger)


class _StdoutHandler(handlers.StreamHandler):
    """Writes to whatever sys.stdout is when a record is emitted (tests swap it)."""

    def __init__(self) -> None:
        super().__init__(sys.stdout)

    @property
    def stream(self) -> TextIO:
        return sys.stdout

    @stream.setter
    def stream(self, _value: TextIO) -> None:
        pass


def default_log_root() -> Path:
    """$ROS_LOG_DIR, else $ROS_HOME/log, else ~/.ros/log (an empty variable counts as unset)."""
    if os.environ.get('ROS_LOG_DIR'):
        return Path(os.path.expanduser(os.environ['ROS_LOG_DIR']))
    if os.environ.get('ROS_HOME'):
        return Path(os.path.expanduser(os.environ['ROS_HOME'])) / 'log'
    return Path.home() / '.ros' / 'log'


def _make_log_dir() -> str:
    """A new <stamp>-<host>-<pid> directory below the log root, which `latest` then points at."""
    stamp = datetime.datetime.now().strftime('%Y-%m-%d-%H-%M-%S-%f')
    root = default_log_root()
    log_dir = root / f'{stamp}-{socket.gethostname()}-{os.getpid()}'
    log_dir.mkdir(parents=True, exist_ok=True)
    latest = root / 'latest'
    try:
        if latest.is_symlink() or not latest.exists():  # never replace a real file or directory
            latest.unlink(missing_ok=True)
            latest.symlink_to(log_dir.name)
    except OSError:
        pass  # `latest` is a convenience; the logs are written all the same
    return str(log_dir)


def _override(variable: str, requested: str | None, style: str | None,
              ) -> tuple[str | None, str | None, str]:
    """The format and style an OVERRIDE_LAUNCH_*_FORMAT variable asks for, else the requested ones.

    The third value says where the format came from, for errors. The variable's value is a
    `{`-style format or an alias; backslash escapes in it (a tab, a newline) are decoded, since a
    shell passes them literally.
    """
    value = os.environ.get(variable)
    if not value:
        return requested, style, 'format'
    try:
        value = value.encode('latin-1', 'backslashreplace').decode('unicode_escape')
    except UnicodeDecodeError as error:
        raise ValueError(f'{variable}={os.environ[variable]!r} has a bad escape: {error.reason}') from None
    return value, None, f'format (${variable})'


def _formatter(chosen: str | None, style: str | None, aliases: dict[str, str], origin: str,
               ) -> logging.Formatter | None:
    """The formatter for a format or one of its aliases; None for no format at all."""
    if chosen is None:
        return None
    if chosen in aliases:
        if style is not None:
            raise ValueError(f'the {chosen!r} format has a style of its own; give no style with it')
        return logging.Formatter(aliases[chosen], style='{')
    try:
        return logging.Formatter(chosen, style=style or '{')  # type: ignore[arg-type]
    except ValueError as error:
        raise ValueError(f'{chosen!r} is not a usable {origin}: {error}') from None


def _detach(handler: logging.Handler) -> None:
    """Take a handler off every launch logger and close it."""
    for logger in LaunchLogger.all_loggers:
        if handler in logger.handlers:
            logger.removeHandler(handler)
    handler.close()


class LaunchConfig:
    """Launch's logging settings and the handlers they make: the screen one and one per log file."""

    def __init__(self) -> None:
        self.file_handlers: dict[str, handlers.Handler] = {}
        self.screen_handler: handlers.StreamHandler | None = None
        self.reset()

    def reset(self) -> None:
        """Level INFO, default formats, no log directory chosen yet; the handlers made so far are closed."""
        for handler in [*self.file_handlers.values(), self.screen_handler]:
            if handler is not None:
                _detach(handler)
        self._log_dir: str | None = None
        self._log_dir_error: str | None = None
        self.file_handlers = {}
        self.screen_handler = None
        self.screen_formatter: logging.Formatter | None = None
        self.file_formatter: logging.Formatter | None = None
        self._log_handler_factory: Callable[..., logging.Handler] | None = None
        # The formats asked for; set up again at each run, so that an OVERRIDE_ variable set since counts.
        self._screen_request: tuple[str | None, str | None] = ('default', None)
        self._log_request: tuple[str | None, str | None] = ('default', None)
        # The loggers get_logger gave out: they write to launch.log too, once there is one.
        self._launch_log_users: set[logging.Logger] = set()
        # A directory set through log_dir, which every run then uses instead of a new one.
        self._chosen_log_dir: str | None = None
        _root.setLevel(logging.INFO)
        self.set_screen_format('default')
        self.set_log_format('default')

    @property
    def level(self) -> int:
        """The level every launch logger without a level of its own logs at."""
        return _root.getEffectiveLevel()

    @level.setter
    def level(self, level: int | str) -> None:
        _root.setLevel(level)

    @property
    def log_dir(self) -> str | None:
        """The directory the log files go to, made on first use; None if it could not be made."""
        if self._log_dir is None and self._log_dir_error is None:
            try:
                self._log_dir = _make_log_dir()
            except OSError as error:
                # Launch goes on without log files rather than stopping for them.
                self._log_dir_error = f'{error.strerror}: {error.filename}'
        return self._log_dir

    @log_dir.setter
    def log_dir(self, log_dir: str | os.PathLike[str] | None) -> None:
        """An existing directory for the log files, or None to have a new one made on next use."""
        if log_dir is not None:
            if not os.path.isdir(log_dir):
                raise ValueError(f'{log_dir} is not a directory')
            if self.file_handlers:
                warnings.warn(f'log files below {self._log_dir} are open already; new ones go to {log_dir}',
                              stacklevel=2)
            log_dir = os.fspath(log_dir)
        self._log_dir = self._chosen_log_dir = log_dir
        self._log_dir_error = None

    @property
    def log_handler_factory(self) -> Callable[..., logging.Handler]:
        """What makes a log file's handler: called with the file's path and `encoding=`."""
        if self._log_handler_factory is None:
            # A watched file is reopened when log rotation moves it away; Windows cannot watch files.
            return handlers.WatchedFileHandler if os.name != 'nt' else handlers.FileHandler
        return self._log_handler_factory

    @log_handler_factory.setter
    def log_handler_factory(self, factory: Callable[..., logging.Handler] | None) -> None:
        self._log_handler_factory = factory

    def set_screen_format(self, screen_format: str | None, *, screen_style: str | None = None) -> None:
        """The format of launch's records on the screen: a logging format or an alias.

        Aliases: 'default' (`[LEVEL] [name]: message`) and 'default_with_timestamp'. A style
        ('%', '{' or '$', default '{') goes only with a format of one's own. $OVERRIDE_LAUNCH_SCREEN_FORMAT,
        when set, wins. None leaves the records unformatted.
        """
        chosen, style, origin = _override('OVERRIDE_LAUNCH_SCREEN_FORMAT', screen_format, screen_style)
        self.screen_formatter = _formatter(chosen, style, SCREEN_FORMAT_ALIASES, f'screen {origin}')
        self._screen_request = (screen_format, screen_style)
        if self.screen_handler is not None:
            self.screen_handler.setFormatter(self.screen_formatter)

    def set_log_format(self, log_format: str | None, *, log_style: str | None = None) -> None:
        """The format of launch's records in the log files: a logging format or 'default'.

        'default' is `<timestamp> [LEVEL] [name]: message`. $OVERRIDE_LAUNCH_LOG_FORMAT, when set,
        wins. The lines of processes keep their own format.
        """
        chosen, style, origin = _override('OVERRIDE_LAUNCH_LOG_FORMAT', log_format, log_style)
        self.file_formatter = _formatter(chosen, style, LOG_FORMAT_ALIASES, f'log {origin}')
        self._log_request = (log_format, log_style)
        for handler in self.file_handlers.values():
            handler.setFormatter(self.file_formatter)

    def get_screen_handler(self) -> handlers.StreamHandler:
        """The one handler that writes to the screen (stdout), made on first use."""
        if self.screen_handler is None:
            self.screen_handler = _StdoutHandler()
            self.screen_handler.setFormatter(self.screen_formatter)
        return self.screen_handler

    def get_log_file_path(self, file_name: str = 'launch.log') -> str:
        """The path of a log file in the log directory."""
        if self.log_dir is None:
            raise RuntimeError(f'launch has no log directory ({self._log_dir_error})')
        return os.path.join(self.log_dir, file_name)

    def get_log_file_handler(self, file_name: str = 'launch.log') -> handlers.Handler:
        """The handler of a log file, made on first use and the same one after.

        Without a log directory it is a handler that drops the records.
        """
        handler = self.file_handlers.get(file_name)
        if handler is not None:
            return handler
        if self.log_dir is None:
            handler = handlers.NullHandler()
        else:
            made = self.log_handler_factory(self.get_log_file_path(file_name), encoding='utf-8')
            if not isinstance(made, handlers.Handler):
                made.close()
                raise TypeError(f'log_handler_factory gave {made!r}; it must give a handler of '
                                'launch.logging.handlers (one with per-logger formatting)')
            handler = made
        handler.setFormatter(self.file_formatter)
        self.file_handlers[file_name] = handler
        if file_name == 'launch.log':
            for logger in self._launch_log_users:
                logger.addHandler(handler)
        return handler

    def _start_run(self) -> None:
        """Close the log files of the last run and open launch.log where this run logs."""
        for handler in self.file_handlers.values():
            _detach(handler)
        self.file_handlers = {}
        self._log_dir = self._chosen_log_dir
        self._log_dir_error = None
        screen_format, screen_style = self._screen_request
        self.set_screen_format(screen_format, screen_style=screen_style)
        log_format, log_style = self._log_request
        self.set_log_format(log_format, log_style=log_style)
        self.get_log_file_handler()


launch_config = LaunchConfig()


def get_logger(name: str | None = None) -> logging.Logger:
    """A logger whose records go to the screen (`[LEVEL] [name]: message` by default) and to launch.log.

    Without a name it is launch's own logger, `launch`. It writes to launch.log once there is a
    log directory (a LaunchService makes one); asking for a logger does not make one.
    """
    logger = _manager.getLogger(name or 'launch')
    logger.addHandler(launch_config.get_screen_handler())  # addHandler adds a handler only once
    launch_config._launch_log_users.add(logger)
    if launch_config._log_dir is not None:
        logger.addHandler(launch_config.get_log_file_handler())
    return logger


def normalize_output_config(output_config: str | dict[str, Any]) -> dict[str, set[str]]:
    """The destinations of stdout, stderr and both ('both' naming the combined own log)."""
    normalized: dict[str, set[str]] = {source: set() for source in OUTPUT_SOURCES}
    if isinstance(output_config, str):
        if output_config not in OUTPUT_ALIASES:
            raise ValueError(f'{output_config!r} is not a valid output configuration: use one of '
                             f'{", ".join(map(repr, OUTPUT_ALIASES))} or a dict')
        normalized.update(OUTPUT_ALIASES[output_config])
        return normalized
    if not isinstance(output_config, dict):
        raise ValueError(f'{output_config!r} is not a valid output configuration: give an alias such as '
                         "'screen' or a dict of sources ('stdout', 'stderr', 'both') to destinations")
    for source, destinations in output_config.items():
        if source not in OUTPUT_SOURCES:
            raise ValueError(f'{source!r} is not a valid output source: use one of '
                             f'{", ".join(OUTPUT_SOURCES)}')
        chosen = {destinations} if isinstance(destinations, str) else destinations
        if not isinstance(chosen, Iterable) or not all(item in OUTPUT_DESTINATIONS for item in chosen):
            raise ValueError(f'{destinations!r} is not a valid output destination of {source}: use one or '
                             f'more of {", ".join(OUTPUT_DESTINATIONS)}')
        normalized[source] = set(chosen)
    return normalized


def _attach(logger: logging.Logger, handler: handlers.Handler, formatter: logging.Formatter) -> None:
    handler.setFormatterFor(logger, formatter)
    logger.addHandler(handler)


def _connect_output(logger: logging.Logger, process_name: str, source: str, destinations: set[str],
                    combined: bool) -> None:
    """Give the logger of one output stream of a process the handlers its destinations need.

    own_log writes <process_name>-<source>.log; `combined` adds <process_name>.log, which both
    streams share.
    """
    if 'screen' in destinations:
        _attach(logger, launch_config.get_screen_handler(), _process_screen_formatter)
    if 'log' in destinations:
        _attach(logger, launch_config.get_log_file_handler(), _process_file_formatter)
    if 'own_log' in destinations:
        _attach(logger, launch_config.get_log_file_handler(f'{process_name}-{source}.log'),
                _process_file_formatter)
    if combined:
        _attach(logger, launch_config.get_log_file_handler(f'{process_name}.log'), _process_file_formatter)


def get_output_loggers(process_name: str, output_config: str | dict[str, Any],
                       ) -> tuple[logging.Logger, logging.Logger]:
    """The loggers for the stdout and stderr lines of a process, sent where `output_config` says.

    output_config is an alias or a dict from a source ('stdout', 'stderr' or 'both') to one or
    more destinations ('screen', 'log' for launch.log, 'own_log' for a file of the process's own:
    <process_name>-stdout.log / -stderr.log, or <process_name>.log for 'both'). The aliases:

    - 'screen': both streams to the screen;
    - 'log': both to launch.log, stderr to the screen as well;
    - 'both': both to the screen and launch.log;
    - 'own_log': each to its own file and both to the combined one;
    - 'full': everywhere.

    A bad alias, source or destination is a ValueError. Asking again adds destinations, never
    removes any.
    """
    config = normalize_output_config(output_config)
    loggers = []
    for source in ('stdout', 'stderr'):
        logger = _manager.getLogger(f'{process_name}-{source}')
        # own_log under 'both' is the combined file, not the file of each stream.
        destinations = (config['both'] - {'own_log'}) | config[source]
        _connect_output(logger, process_name, source, destinations, combined='own_log' in config['both'])
        loggers.append(logger)
    return loggers[0], loggers[1]


def setup_log_dir() -> str | None:
    """Start a run: its log directory, whose launch.log launch's loggers write to from now on.

    That is a new directory, unless one was set through `launch_config.log_dir`. Formats are set
    up again, so that an OVERRIDE_LAUNCH_*_FORMAT variable set since counts. Returns the
    directory, or None when it cannot be made (the run then goes on without log files).
    """
    launch_config._start_run()
    return launch_config.log_dir


def log_launch_config(logger: logging.Logger | None = None) -> None:
    """The two lines every launch starts with."""
    logger = logger or get_logger()
    where = launch_config.log_dir if launch_config.log_dir is not None else '(no log directory)'
    logger.info(f'All log files can be found below {where}')
    logger.info(f'Default logging verbosity is set to {logging.getLevelName(launch_config.level)}')


def close_process_logs() -> None:
    """Close the files of processes' own logs at the end of a run; launch.log stays open."""
    for file_name in [name for name in launch_config.file_handlers if name != 'launch.log']:
        _detach(launch_config.file_handlers.pop(file_name))


def reset() -> None:
    """Logging as it was at import: launch loggers without level or handlers, launch_config reset."""
    for logger in LaunchLogger.all_loggers:
        logger.setLevel(logging.NOTSET)
        logger.handlers.clear()
    launch_config.reset()
