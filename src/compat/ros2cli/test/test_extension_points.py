"""Entry point discovery and the plug-in rules, without a ROS graph."""

import argparse

import pytest
import ros2cli.command
from ros2cli import entry_points
from ros2cli.command import CommandExtension, _chosen_name, add_subparsers
from ros2cli.entry_points import EntryPoint, _parse, get_entry_points, get_first_line_doc
from ros2cli.plugin_system import PluginException, satisfies_version
from ros2cli.verb import VerbExtension


def test_entry_points_text_is_read_per_group_first_declaration_wins():
    found = {}
    _parse('[ros2cli.command]\nhello = pkg.command:Hello\n# a comment\n\n[other]\nx=y:z\nno equals sign\n',
           found)
    _parse('[ros2cli.command]\nhello = shadowed.command:Hello\n', found)
    assert found['ros2cli.command']['hello'].value == 'pkg.command:Hello'
    assert found['other']['x'].value == 'y:z'
    assert list(found['other']) == ['x']


def test_the_installed_commands_and_verbs_are_entry_points():
    assert {'action', 'daemon', 'interface', 'launch', 'node', 'param', 'pkg', 'run', 'service',
            'topic'} <= set(get_entry_points('ros2cli.command'))
    assert set(get_entry_points('ros2pkg.verb')) == {'create', 'executables', 'list', 'prefix', 'xml'}
    assert get_entry_points('no.such.group') == {}


def test_the_entry_points_are_those_importlib_metadata_finds():
    from importlib.metadata import distributions
    expected: dict = {}
    for distribution in distributions():
        _parse(distribution.read_text('entry_points.txt') or '', expected)
    assert {group: {name: point.value for name, point in points.items()}
            for group, points in entry_points._all_entry_points().items()} == {
        group: {name: point.value for name, point in points.items()} for group, points in expected.items()}


def test_an_entry_point_loads_what_its_value_names():
    method = EntryPoint('p', 'argparse:ArgumentParser.add_argument', 'g')
    assert method.load() is argparse.ArgumentParser.add_argument
    assert EntryPoint('p', 'argparse : ArgumentParser [extra]', 'g').load() is argparse.ArgumentParser
    assert EntryPoint('p', 'argparse', 'g').load() is argparse
    with pytest.raises(AttributeError):
        EntryPoint('p', 'argparse:NoSuchThing', 'g').load()


def test_a_broken_entry_point_is_one_warning_line(capsys, monkeypatch):
    monkeypatch.setattr(entry_points, '_BY_GROUP', {'g': {
        'bad': EntryPoint(name='bad', value='no_such_module_here:X', group='g'),
        'good': EntryPoint(name='good', value='argparse:ArgumentParser', group='g')}})
    assert entry_points.load_entry_points('g') == {'good': argparse.ArgumentParser}
    err = capsys.readouterr().err
    assert err == ("ros2: warning: skipped 'bad' of 'g' (no_such_module_here:X): ModuleNotFoundError: "
                   "No module named 'no_such_module_here'\n")


def test_first_line_of_the_docstring_without_its_period():
    class Documented:
        """

        Various things.
        More.
        """  # noqa: D205 -- the shape under test: only the first non-blank line counts
    assert get_first_line_doc(Documented) == 'Various things'
    assert get_first_line_doc(object()) == 'The base class of the class hierarchy'
    assert get_first_line_doc(type('Bare', (), {'__doc__': None})) == ''


@pytest.mark.parametrize(('version', 'caret', 'fits'), [
    ('0.1', '^0.1', True), ('0.1.5', '^0.1', True), ('0.2', '^0.1', False), ('0.0', '^0.1', False),
    ('1.4', '^1.2', True), ('2.0', '^1.2', False), ('1.1', '^1.2', False)])
def test_caret_ranges(version, caret, fits):
    if fits:
        satisfies_version(version, caret)
    else:
        with pytest.raises(PluginException):
            satisfies_version(version, caret)


def test_bad_version_text_is_a_plugin_exception():
    with pytest.raises(PluginException, match=r"'0\.x' is not a version"):
        satisfies_version('0.x', '^0.1')
    with pytest.raises(PluginException, match='not a caret range'):
        satisfies_version('0.1', '0.1')


def test_the_chosen_word_at_each_depth(monkeypatch):
    monkeypatch.setattr(ros2cli.command, 'ARGV', ['--use-python-default-buffering', 'topic', 'echo', '/x'])
    assert _chosen_name('ros2', None) == 'topic'
    assert _chosen_name('ros2 topic', None) == 'echo'
    assert _chosen_name('ros2 topic echo', ['topic']) is None


def test_subparsers_list_docstrings_and_set_the_chosen_extension():
    class Greet(VerbExtension):
        """Say hello."""

        def add_arguments(self, parser, cli_name):
            parser.add_argument('--name', default='world')

    class Hello(CommandExtension):
        """Greet."""

    parser = argparse.ArgumentParser(prog='ros2 hello')
    add_subparsers(parser, 'ros2 hello', '_verb', {'greet': Greet(), 'hello': Hello()}, required=False)
    assert '\n  greet  Say hello\n  hello  Greet\n' in parser.format_help()
    args = parser.parse_args(['greet', '--name', 'Owl'])
    assert isinstance(args._verb, Greet)
    assert args.name == 'Owl'
    assert not hasattr(parser.parse_args([]), '_verb')
