"""ament_pep257: pydocstyle's rules in ament's convention (checked with ruff), and its errors."""

import pytest
from ament_pep257.main import main

# ROS 2's docstring layout: a multi-line docstring's summary on the line after the quotes.
AMENT_STYLE = '''def f():
    """
    Return one.

    More about it.
    """
    return 1


def g():
    return 2
'''
# The layout PEP 257 itself shows, which ament's convention refuses (D213).
SUMMARY_ON_FIRST_LINE = '''"""A module with every docstring."""


def f():
    """Return one.

    More about it.
    """
    return 1
'''


def check(tmp_path, monkeypatch, source, *argv):
    monkeypatch.chdir(tmp_path)
    (tmp_path / 'code.py').write_text(source)
    return main(argv=list(argv))


def test_ament_layout_passes_and_missing_docstrings_are_fine(tmp_path, monkeypatch, capsys):
    assert check(tmp_path, monkeypatch, AMENT_STYLE) == 0
    assert capsys.readouterr().out == 'checking code.py\nNo problems found\n'


def test_the_ament_convention_wants_the_summary_on_the_second_line(tmp_path, monkeypatch, capsys):
    assert check(tmp_path, monkeypatch, SUMMARY_ON_FIRST_LINE) == 1
    assert capsys.readouterr().err == ('code.py:5 D213: Multi-line docstring summary should start at '
                                       'the second line\n1 errors\n')


@pytest.mark.parametrize(('argv', 'rc'), [
    (['--convention', 'pep257'], 0),      # pydocstyle's preset, without D213
    (['--add-ignore', 'D213'], 0),
    (['--ignore', 'D213'], 0),            # every other rule, D100-D107 included
    (['--select', 'D400'], 0),
    (['--select', 'D212'], 0),
    (['--select', 'D213'], 1),
])
def test_rule_set_options(tmp_path, monkeypatch, argv, rc):
    assert check(tmp_path, monkeypatch, SUMMARY_ON_FIRST_LINE, *argv, '--', '.') == rc


def test_ignore_alone_checks_missing_docstrings_too(tmp_path, monkeypatch):
    assert check(tmp_path, monkeypatch, AMENT_STYLE, '--ignore', 'D212', '--', '.') == 1  # g has none


@pytest.mark.parametrize(('argv', 'message'), [
    (['missing'], 'ament_pep257: missing: no such file or directory\n'),
    (['--select', 'E501', '--', '.'], "ament_pep257: 'E501' is not a docstring rule (codes start with D)\n"),
])
def test_bad_input_is_one_clear_line(tmp_path, monkeypatch, capsys, argv, message):
    assert check(tmp_path, monkeypatch, 'x = 1\n', *argv) == 1
    assert capsys.readouterr().err == message
