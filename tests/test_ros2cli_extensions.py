"""`ros2` finds its commands and verbs through entry points, as upstream ros2cli does.

A third party's package, built with colcon into a workspace of its own, adds `ros2 hello` without
ros2cli naming it, and a package whose command cannot be imported costs one warning line, not the
rest of `ros2`.

The two packages (tests/ros2_extensions) are written against upstream's extension API
(CommandExtension, add_subparsers_on_demand, VerbExtension, their entry point groups).
"""

import re
from pathlib import Path

import pytest
from student_workspace import shared_build, shell

EXTENSIONS = Path(__file__).resolve().parent / 'ros2_extensions'


@pytest.fixture(scope='module')
def workspace(tmp_path_factory):
    """A workspace with ros2hello and ros2broken in src/, built as a student builds one."""
    return shared_build(tmp_path_factory, [EXTENSIONS / 'ros2hello', EXTENSIONS / 'ros2broken'])


def warnings(result):
    return [line for line in result.stderr.splitlines() if line.startswith('ros2: warning:')]


def test_a_third_party_command_is_listed_by_ros2_help_and_runs(workspace):
    top = shell(workspace, 'ros2 -h')
    assert top.returncode == 0, top.stderr
    assert re.search(r"\n  hello +Greet the world from a third party's package\n", top.stdout), top.stdout
    # The commands of ros2cli, ros2pkg and ros2launch are found the same way.
    for name, description in (('launch', 'Run a launch file'),
                              ('pkg', 'Various package related sub-commands'),
                              ('topic', 'Various topic related sub-commands')):
        assert re.search(f'\n  {name} +{description}\n', top.stdout)
    hello = shell(workspace, 'ros2 hello')
    assert hello.returncode == 0, hello
    assert '\n  world  Print a greeting\n' in hello.stdout, hello
    world = shell(workspace, 'ros2 hello world --name Owl --times 2')
    assert world.returncode == 0, world.stderr
    assert world.stdout == 'hello, Owl (from the package ros2hello)\n' * 2


def test_a_third_party_verb_says_bad_input_in_one_line(workspace):
    result = shell(workspace, 'ros2 hello world --times 0')
    assert result.returncode == 1, result
    assert result.stderr == '--times must be at least 1, got 0\n', result
    typo = shell(workspace, 'ros2 hello wrld')
    assert typo.returncode == 2
    assert "invalid choice: 'wrld' (choose from 'world')" in typo.stderr
    assert 'Traceback' not in typo.stderr


def test_a_broken_extension_is_one_warning_line_and_the_rest_works(workspace):
    top = shell(workspace, 'ros2 -h')
    assert top.returncode == 0
    assert warnings(top) == [
        "ros2: warning: skipped 'broken' of 'ros2cli.command' (ros2broken.command:BrokenCommand): "
        "ModuleNotFoundError: No module named 'a_module_that_is_not_installed'"], top.stderr
    assert top.stderr.count('\n') == 1
    assert 'Traceback' not in top.stderr
    assert '\n  broken ' not in top.stdout
    assert '\n  hello ' in top.stdout
    # Only the chosen command is imported: the broken one costs nothing elsewhere.
    listing = shell(workspace, 'ros2 pkg prefix ros2hello')
    assert listing.returncode == 0
    assert listing.stderr == ''
    assert listing.stdout.strip() == str(workspace / 'install' / 'ros2hello')
    chosen = shell(workspace, 'ros2 broken')
    assert chosen.returncode == 2
    assert len(warnings(chosen)) == 1
    assert "invalid choice: 'broken'" in chosen.stderr
    assert 'Traceback' not in chosen.stderr


def test_ros2_extensions_lists_them_and_says_why_one_fails(workspace):
    listing = shell(workspace, 'ros2 extensions -a')
    assert listing.returncode == 0
    assert listing.stderr == ''
    assert "\n  hello: Greet the world from a third party's package\n" in listing.stdout
    assert '\nros2hello.verb:\n  world: Print a greeting\n' in listing.stdout
    assert ("\n  broken: failed to load: ModuleNotFoundError: No module named "
            "'a_module_that_is_not_installed'\n") in listing.stdout
    quiet = shell(workspace, 'ros2 extensions')
    assert quiet.returncode == 0
    assert len(warnings(quiet)) == 1
    assert '  broken' not in quiet.stdout
    points = shell(workspace, 'ros2 extension_points')
    assert "ros2hello.verb: The extension point for a command's verbs (the base class of a verb)" \
        in points.stdout.splitlines()
    wrong = shell(workspace, 'ros2 extensions --nope')
    assert wrong.returncode == 2
    assert 'unrecognized arguments: --nope' in wrong.stderr


def test_without_the_workspace_the_third_party_command_is_gone(workspace):
    result = shell(workspace / 'src', 'ros2 -h')  # src/ has no install/: the base environment only
    assert result.returncode == 0
    assert '\n  hello ' not in result.stdout
    assert warnings(result) == []
