"""The `owl` dispatcher: its commands come from the owl_cli.command entry points."""

import argparse

import pytest
from owl_cli import main as owl
from owl_cli.command import Command


def test_every_command_is_found_through_its_entry_point():
    found = owl.commands()
    assert list(found) == ['check', 'class', 'demo', 'network', 'pages', 'windows']
    for name, command in found.items():
        assert isinstance(command, Command), name
        assert type(command).__module__ == f"owl_cli.{'classroom' if name == 'class' else name}.command"
        assert command.help, name


class Shout(Command):
    """A command for the test: says what it was given, or is stopped with Ctrl-C."""

    help = 'say it'

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        parser.add_argument('words', nargs='*')
        parser.set_defaults(cli_name=cli_name)

    def main(self, *, parser: argparse.ArgumentParser, args: argparse.Namespace) -> int:
        if args.words == ['ctrl-c']:
            raise KeyboardInterrupt
        if not args.words:
            parser.error('say something')
        print(args.cli_name, *args.words)
        return 7


def test_the_chosen_command_runs_with_its_own_parser_and_ctrl_c_gives_130(monkeypatch, capsys):
    monkeypatch.setattr(owl, 'commands', lambda: {'shout': Shout()})
    assert owl.main(['shout', 'hello']) == 7
    assert capsys.readouterr().out == 'owl shout hello\n'
    assert owl.main(['shout', 'ctrl-c']) == 130
    with pytest.raises(SystemExit) as stopped:
        owl.main(['shout'])
    assert stopped.value.code == 2
    assert capsys.readouterr().err.splitlines()[-1] == 'owl shout: error: say something'
