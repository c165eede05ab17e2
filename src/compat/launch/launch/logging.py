"""Launch's own output: `[LEVEL] [logger]: message` on the screen (stdout) and a launch.log on disk.

The loggers live in a logging tree of their own, so that launch's output neither reaches nor
depends on the Python root logger of the program that embeds launch.
"""

from __future__ import annotations

import datetime
import logging
import os
import socket
import sys
from pathlib import Path
from typing import TextIO

SCREEN_FORMAT = '[{levelname}] [{name}]: {msg}'
LOG_FILE_FORMAT = '{created:.7f} [{levelname}] [{name}]: {msg}'
# A process's output lines are already `[label] line`; on disk they get a timestamp.
PROCESS_LOG_FILE_FORMAT = '{created:.7f} {msg}'
# Names usable in OVERRIDE_LAUNCH_SCREEN_FORMAT / OVERRIDE_LAUNCH_LOG_FORMAT besides a format.
FORMAT_ALIASES = {'default': SCREEN_FORMAT, 'default_with_timestamp': LOG_FILE_FORMAT}


def _format(variable: str, default: str) -> logging.Formatter:
    """The format an OVERRIDE_LAUNCH_*_FORMAT variable asks for, else the default."""
    chosen = os.environ.get(variable) or default
    return logging.Formatter(FORMAT_ALIASES.get(chosen, chosen), style='{')

_root = logging.RootLogger(logging.INFO)
_manager = logging.Manager(_root)


class _StdoutHandler(logging.StreamHandler):
    """Writes to whatever sys.stdout is when a record is emitted (tests swap it)."""

    def __init__(self) -> None:
        super().__init__(sys.stdout)

    @property
    def stream(self) -> TextIO:
        return sys.stdout

    @stream.setter
    def stream(self, _value: TextIO) -> None:
        pass


class _Config:
    """Where launch writes: the screen handler always, files once a log directory is set up."""

    def __init__(self) -> None:
        self.screen = _StdoutHandler()
        self.screen.setFormatter(_format('OVERRIDE_LAUNCH_SCREEN_FORMAT', SCREEN_FORMAT))
        _root.addHandler(self.screen)
        self.log_dir: Path | None = None
        self.file_handler: logging.FileHandler | None = None
        self._process_files: dict[str, logging.Logger] = {}

    @property
    def level(self) -> int:
        return _root.level

    @level.setter
    def level(self, level: int) -> None:
        _root.setLevel(level)


launch_config = _Config()


def get_logger(name: str = 'launch') -> logging.Logger:
    """A logger whose records are shown as `[LEVEL] [name]: message`."""
    return _manager.getLogger(name)


def default_log_root() -> Path:
    """$ROS_LOG_DIR, else $ROS_HOME/log, else ~/.ros/log."""
    if os.environ.get('ROS_LOG_DIR'):
        return Path(os.path.expanduser(os.environ['ROS_LOG_DIR']))
    if os.environ.get('ROS_HOME'):
        return Path(os.path.expanduser(os.environ['ROS_HOME'])) / 'log'
    return Path.home() / '.ros' / 'log'


def setup_log_dir() -> Path | None:
    """Create this run's log directory and send launch's records to its launch.log as well."""
    if launch_config.file_handler is not None:
        _root.removeHandler(launch_config.file_handler)
        launch_config.file_handler.close()
        launch_config.file_handler = None
    launch_config._process_files.clear()
    launch_config.screen.setFormatter(_format('OVERRIDE_LAUNCH_SCREEN_FORMAT', SCREEN_FORMAT))
    stamp = datetime.datetime.now().strftime('%Y-%m-%d-%H-%M-%S-%f')
    root = default_log_root()
    log_dir = root / f'{stamp}-{socket.gethostname()}-{os.getpid()}'
    try:
        log_dir.mkdir(parents=True, exist_ok=True)
        latest = root / 'latest'
        if latest.is_symlink() or not latest.exists():
            latest.unlink(missing_ok=True)
            latest.symlink_to(log_dir.name)
        handler = logging.FileHandler(log_dir / 'launch.log', encoding='utf-8')
    except OSError:
        launch_config.log_dir = None  # an unwritable log root must not stop the launch
        return None
    handler.setFormatter(_format('OVERRIDE_LAUNCH_LOG_FORMAT', LOG_FILE_FORMAT))
    _root.addHandler(handler)
    launch_config.file_handler = handler
    launch_config.log_dir = log_dir
    return log_dir


def log_launch_config(logger: logging.Logger) -> None:
    """The two lines every launch starts with."""
    where = launch_config.log_dir if launch_config.log_dir is not None else '(no log directory)'
    logger.info(f'All log files can be found below {where}')
    logger.info(f'Default logging verbosity is set to {logging.getLevelName(launch_config.level)}')


def _process_file_logger(file_name: str) -> logging.Logger:
    """A logger writing only to <log_dir>/<file_name>, created on first use."""
    logger = launch_config._process_files.get(file_name)
    if logger is None:
        logger = logging.Logger(file_name, logging.DEBUG)
        if launch_config.log_dir is not None:
            handler = logging.FileHandler(launch_config.log_dir / file_name, encoding='utf-8')
            handler.setFormatter(logging.Formatter(PROCESS_LOG_FILE_FORMAT, style='{'))
            logger.addHandler(handler)
        launch_config._process_files[file_name] = logger
    return logger


def write_process_line(text: str, label: str, stream: str, destinations: set[str]) -> None:
    """One output line of a child process to the destinations its `output` setting chose.

    destinations: any of 'screen', 'log' (launch.log) and 'own_log' (<label>-<stream>.log and
    <label>.log).
    """
    if 'screen' in destinations:
        sys.stdout.write(text + '\n')
        sys.stdout.flush()
    if 'log' in destinations and launch_config.file_handler is not None:
        _process_file_logger('launch.log').info(text)
    if 'own_log' in destinations:
        _process_file_logger(f'{label}-{stream}.log').info(text)
        _process_file_logger(f'{label}.log').info(text)


def close_process_logs() -> None:
    for logger in launch_config._process_files.values():
        for handler in list(logger.handlers):
            handler.close()
            logger.removeHandler(handler)
    launch_config._process_files.clear()
