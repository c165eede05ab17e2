"""launch.logging's public functions, as third-party code (launch_testing, custom frontends) uses them."""

import logging
import logging.handlers
import os
import re

import launch.logging
import pytest
from launch import LaunchDescription, LaunchService
from launch.actions import LogInfo
from launch.logging import handlers, launch_config

TIMESTAMP = r'\d+\.\d+'


@pytest.fixture(autouse=True)
def fresh_logging(tmp_path, monkeypatch):
    """Each test starts from logging as at import, with logs below tmp_path, and leaves it so."""
    monkeypatch.setenv('ROS_LOG_DIR', str(tmp_path / 'log'))
    monkeypatch.delenv('OVERRIDE_LAUNCH_SCREEN_FORMAT', raising=False)
    monkeypatch.delenv('OVERRIDE_LAUNCH_LOG_FORMAT', raising=False)
    launch.logging.reset()
    yield
    launch.logging.reset()


@pytest.fixture
def log_dir(tmp_path):
    chosen = tmp_path / 'chosen'
    chosen.mkdir()
    launch_config.log_dir = str(chosen)
    return chosen


def file_lines(log_dir, name='launch.log'):
    for handler in launch_config.file_handlers.values():
        handler.flush()
    path = log_dir / name
    return path.read_text().splitlines() if path.exists() else []


def test_the_public_names_are_upstreams():
    assert sorted(launch.logging.__all__) == ['get_logger', 'get_output_loggers', 'handlers', 'launch_config',
                                              'reset']
    assert isinstance(launch_config, launch.logging.LaunchConfig)
    import launch.logging.handlers as by_path
    assert by_path is handlers


def test_get_logger_shows_level_and_name_on_the_screen(capsys):
    launch.logging.get_logger('my.node').info('hello')
    launch.logging.get_logger().warning('from launch')
    assert capsys.readouterr().out.splitlines() == ['[INFO] [my.node]: hello',
                                                    '[WARNING] [launch]: from launch']


def test_a_handler_added_again_by_the_caller_does_not_repeat_lines(capsys, log_dir):
    logger = launch.logging.get_logger('twice')
    logger.addHandler(launch_config.get_screen_handler())
    logger.addHandler(launch_config.get_log_file_handler())
    logger.info('once')
    assert capsys.readouterr().out.splitlines() == ['[INFO] [twice]: once']
    assert len(file_lines(log_dir)) == 1


def test_a_logger_taken_before_there_is_a_log_directory_writes_to_launch_log_once_there_is(tmp_path):
    early = launch.logging.get_logger('early')
    assert not (tmp_path / 'log').exists()  # asking for a logger makes no directory
    launch.logging.setup_log_dir()
    early.error('now on disk')
    assert re.fullmatch(rf'{TIMESTAMP} \[ERROR\] \[early\]: now on disk',
                        file_lines(tmp_path / 'log' / 'latest')[0])


def test_launch_loggers_stay_out_of_the_python_root_logger(caplog):
    launch.logging.get_logger('private').info('not for the root logger')
    assert caplog.records == []
    assert logging.getLoggerClass() is logging.Logger


def test_level_is_info_and_applies_to_every_launch_logger(capsys):
    logger = launch.logging.get_logger('levels')
    assert launch_config.level == logging.INFO
    logger.debug('hidden')
    launch_config.level = logging.DEBUG
    logger.debug('shown')
    assert capsys.readouterr().out.splitlines() == ['[DEBUG] [levels]: shown']


def test_log_dir_is_made_on_first_use_below_ros_log_dir_with_latest_pointing_at_it(tmp_path):
    made = launch_config.log_dir
    assert isinstance(made, str)
    assert os.path.dirname(made) == str(tmp_path / 'log')
    assert os.path.isdir(made)
    assert (tmp_path / 'log' / 'latest').resolve() == (tmp_path / 'log' / os.path.basename(made)).resolve()
    assert launch_config.log_dir == made
    assert launch_config.get_log_file_path('x.log') == os.path.join(made, 'x.log')


def test_log_dir_must_be_an_existing_directory(tmp_path):
    with pytest.raises(ValueError, match='is not a directory'):
        launch_config.log_dir = str(tmp_path / 'missing')


def test_an_unwritable_log_root_leaves_launch_without_files_not_broken(tmp_path, monkeypatch, capsys):
    (tmp_path / 'a_file').write_text('')
    monkeypatch.setenv('ROS_LOG_DIR', str(tmp_path / 'a_file' / 'log'))
    assert launch_config.log_dir is None
    assert isinstance(launch_config.get_log_file_handler(), logging.NullHandler)
    with pytest.raises(RuntimeError, match='no log directory'):
        launch_config.get_log_file_path()
    launch.logging.get_logger('nowhere').info('still on screen')
    assert capsys.readouterr().out == '[INFO] [nowhere]: still on screen\n'


def test_a_chosen_log_dir_is_the_one_a_launch_service_writes_to(log_dir):
    service = LaunchService(noninteractive=True)
    service.include_launch_description(LaunchDescription([LogInfo(msg='kept here')]))
    assert service.run() == 0
    assert any(line.endswith('[INFO] [launch.user]: kept here') for line in file_lines(log_dir))


def test_the_log_file_handler_is_one_per_file(log_dir):
    handler = launch_config.get_log_file_handler()
    assert launch_config.get_log_file_handler('launch.log') is handler
    assert launch_config.get_log_file_handler('other.log') is not handler
    assert launch_config.file_handlers['launch.log'] is handler
    assert isinstance(handler, logging.handlers.WatchedFileHandler)
    assert handler.baseFilename == str(log_dir / 'launch.log')


def test_screen_format_aliases_styles_and_errors(capsys):
    logger = launch.logging.get_logger('fmt')
    launch_config.set_screen_format('default_with_timestamp')
    logger.info('a')
    launch_config.set_screen_format('%(levelname)s|%(message)s', screen_style='%')
    logger.info('b')
    launch_config.set_screen_format('default')
    logger.info('c')
    out = capsys.readouterr().out
    assert re.fullmatch(rf'{TIMESTAMP} \[INFO\] \[fmt\]: a\nINFO\|b\n\[INFO\] \[fmt\]: c\n', out)
    with pytest.raises(ValueError, match='style of its own'):
        launch_config.set_screen_format('default', screen_style='%')
    with pytest.raises(ValueError, match=re.escape("'{oops' is not a usable screen format")):
        launch_config.set_screen_format('{oops')


def test_log_format_default_has_a_timestamp_and_a_custom_one_applies_to_open_files(log_dir):
    logger = launch.logging.get_logger('disk')
    logger.info('first')
    launch_config.set_log_format('{levelname}:{msg}')
    logger.info('second')
    first, second = file_lines(log_dir)
    assert re.fullmatch(rf'{TIMESTAMP} \[INFO\] \[disk\]: first', first)
    assert second == 'INFO:second'
    with pytest.raises(ValueError, match='style of its own'):
        launch_config.set_log_format('default', log_style='%')


def test_override_variables_win_and_their_escapes_are_decoded(monkeypatch, capsys, log_dir):
    monkeypatch.setenv('OVERRIDE_LAUNCH_SCREEN_FORMAT', r'{name}\t{msg}')
    monkeypatch.setenv('OVERRIDE_LAUNCH_LOG_FORMAT', 'LOG {msg}')
    launch_config.set_screen_format('default')
    launch_config.set_log_format('default')
    launch.logging.get_logger('env').info('x')
    assert capsys.readouterr().out == 'env\tx\n'
    assert file_lines(log_dir) == ['LOG x']
    monkeypatch.setenv('OVERRIDE_LAUNCH_SCREEN_FORMAT', '{broken')
    with pytest.raises(ValueError, match=r'\$OVERRIDE_LAUNCH_SCREEN_FORMAT'):
        launch_config.set_screen_format('default')
    monkeypatch.delenv('OVERRIDE_LAUNCH_SCREEN_FORMAT')  # reset() after the test reads it


def test_a_custom_log_handler_factory_makes_the_file_handlers(log_dir):
    written = {}

    class Collecting(handlers.Handler):
        def __init__(self, path, encoding=None):
            super().__init__()
            self.path = path

        def emit(self, record):
            written.setdefault(self.path, []).append(self.format(record))

    launch_config.log_handler_factory = Collecting
    launch.logging.get_logger('custom').warning('caught')
    [line] = written[str(log_dir / 'launch.log')]
    assert line.endswith('[WARNING] [custom]: caught')


def test_a_log_handler_factory_without_per_logger_formatting_is_refused(log_dir):
    launch_config.log_handler_factory = logging.FileHandler
    with pytest.raises(TypeError, match='per-logger formatting'):
        launch_config.get_log_file_handler()


# Where a stdout line ('out') and a stderr line ('err') of a process end up for each `output`.
ROUTES = {
    'screen': {'screen': ['out', 'err'], 'log': [], 'stdout': None, 'stderr': None, 'both': None},
    'log': {'screen': ['err'], 'log': ['out', 'err'], 'stdout': None, 'stderr': None, 'both': None},
    'both': {'screen': ['out', 'err'], 'log': ['out', 'err'], 'stdout': None, 'stderr': None, 'both': None},
    'own_log': {'screen': [], 'log': [], 'stdout': ['out'], 'stderr': ['err'], 'both': ['out', 'err']},
    'full': {'screen': ['out', 'err'], 'log': ['out', 'err'], 'stdout': ['out'], 'stderr': ['err'],
             'both': ['out', 'err']},
    'per stream': {'screen': ['out'], 'log': ['out'], 'stdout': None, 'stderr': ['err'], 'both': None},
    'combined only': {'screen': [], 'log': [], 'stdout': None, 'stderr': None, 'both': ['out', 'err']},
}
CONFIGS = {'per stream': {'stdout': {'screen', 'log'}, 'stderr': 'own_log'},
           'combined only': {'both': ['own_log']}}


@pytest.mark.parametrize('name', ROUTES)
def test_get_output_loggers_sends_each_stream_where_the_config_says(name, capsys, log_dir):
    route = ROUTES[name]
    stdout_logger, stderr_logger = launch.logging.get_output_loggers('proc', CONFIGS.get(name, name))
    assert (stdout_logger.name, stderr_logger.name) == ('proc-stdout', 'proc-stderr')
    stdout_logger.info('out')
    stderr_logger.info('err')
    # Lines of processes are shown as they are, and get a timestamp in files.
    assert capsys.readouterr().out.splitlines() == route['screen']
    assert [line.split(' ', 1)[1] for line in file_lines(log_dir)] == route['log']
    for source, suffix in (('stdout', '-stdout'), ('stderr', '-stderr'), ('both', '')):
        lines = file_lines(log_dir, f'proc{suffix}.log')
        if route[source] is None:
            assert lines == []
        else:
            assert [line.split(' ', 1)[1] for line in lines] == route[source]
            assert all(re.match(TIMESTAMP + ' ', line) for line in lines)


def test_asking_for_output_loggers_again_adds_destinations(capsys, log_dir):
    launch.logging.get_output_loggers('again', 'screen')
    stdout_logger, _ = launch.logging.get_output_loggers('again', 'log')
    stdout_logger.info('twice configured')
    assert capsys.readouterr().out == 'twice configured\n'
    assert len(file_lines(log_dir)) == 1


@pytest.mark.parametrize(('config', 'message'), [
    ('loud', "'loud' is not a valid output configuration"),
    ({'stdin': 'screen'}, "'stdin' is not a valid output source"),
    ({'stdout': 'printer'}, "'printer' is not a valid output destination of stdout"),
    ({'stderr': {'screen', 'both'}}, 'is not a valid output destination of stderr'),
    ({'stdout': 3}, '3 is not a valid output destination of stdout'),
    (['screen'], "is not a valid output configuration: give an alias such as 'screen'"),
])
def test_a_bad_output_config_is_a_clear_value_error(config, message, log_dir):
    with pytest.raises(ValueError, match=re.escape(message)):
        launch.logging.get_output_loggers('bad', config)


def test_handlers_give_every_logging_handler_per_logger_formatting():
    rotating = handlers.RotatingFileHandler
    assert issubclass(rotating, handlers.Handler)
    assert issubclass(rotating, logging.handlers.RotatingFileHandler)
    assert handlers.RotatingFileHandler is rotating
    assert issubclass(handlers.StreamHandler, logging.StreamHandler)
    assert handlers.DEFAULT_TCP_LOGGING_PORT == logging.handlers.DEFAULT_TCP_LOGGING_PORT
    with pytest.raises(AttributeError, match='no attribute'):
        handlers.NoSuchHandler  # noqa: B018
    wrapped = handlers.with_per_logger_formatting(logging.Handler)
    assert issubclass(wrapped, handlers.Handler)
    assert handlers.with_per_logger_formatting(handlers.StreamHandler) is handlers.StreamHandler


def test_set_formatter_for_formats_one_loggers_records_its_own_way():
    handler = handlers.Handler()
    handler.setFormatter(logging.Formatter('{name}: {msg}', style='{'))
    handler.setFormatterFor('special', logging.Formatter('<{msg}>', style='{'))
    special = logging.LogRecord('special', logging.INFO, __file__, 1, 'hi', None, None)
    plain = logging.LogRecord('plain', logging.INFO, __file__, 1, 'hi', None, None)
    assert (handler.format(special), handler.format(plain)) == ('<hi>', 'plain: hi')
    handler.unsetFormatterFor(logging.getLogger('special'))
    handler.unsetFormatterFor('never set')
    assert handler.format(special) == 'special: hi'


def test_reset_returns_logging_to_its_state_at_import(capsys, log_dir, tmp_path):
    logger = launch.logging.get_logger('changed')
    logger.setLevel(logging.ERROR)
    logger.addHandler(logging.NullHandler())
    launch.logging.get_output_loggers('proc', 'full')
    launch_config.level = logging.DEBUG
    launch_config.set_screen_format('{msg}')
    launch_config.log_handler_factory = handlers.FileHandler

    launch.logging.reset()

    assert launch_config.level == logging.INFO
    assert launch_config.screen_handler is None
    assert launch_config.file_handlers == {}
    assert launch_config.log_handler_factory is handlers.WatchedFileHandler
    assert logger.handlers == []
    assert logger.level == logging.NOTSET
    assert logger in launch.logging.LaunchLogger.all_loggers
    assert all(not each.handlers for each in launch.logging.LaunchLogger.all_loggers)
    # The chosen directory is forgotten: the next one is made below ROS_LOG_DIR.
    assert os.path.dirname(launch_config.log_dir) == str(tmp_path / 'log')
    capsys.readouterr()
    launch.logging.get_logger('changed').info('as new')
    assert capsys.readouterr().out == '[INFO] [changed]: as new\n'
