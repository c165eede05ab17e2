"""ament_flake8: ament's flake8 rules (checked with ruff), its report and its errors."""

import pytest
from ament_flake8.main import main, main_with_errors

# A node as the ROS 2 tutorials write it: a blank line inside the third-party imports, which
# ament's configuration accepts (I202 is ignored).
TUTORIAL_NODE = '''import rclpy
from rclpy.node import Node

from std_msgs.msg import String


class MinimalPublisher(Node):

    def __init__(self):
        super().__init__('minimal_publisher')
        self.publisher_ = self.create_publisher(String, 'topic', 10)


def main(args=None):
    rclpy.init(args=args)
    print(2*3)
'''


def errors_in(tmp_path, monkeypatch, source, *argv):
    monkeypatch.chdir(tmp_path)
    (tmp_path / 'code.py').write_text(source)
    return main_with_errors(argv=list(argv))


def test_clean_code_passes_and_the_report_lists_the_files(tmp_path, monkeypatch, capsys):
    assert errors_in(tmp_path, monkeypatch, TUTORIAL_NODE) == (0, [])
    out = capsys.readouterr().out
    assert '1 files checked\nNo problems found\n' in out
    assert out.endswith('Checked files:\n\n* code.py\n')


@pytest.mark.parametrize(('source', 'code'), [
    ('x = "double"\n', 'Q000'),            # flake8-quotes: single quotes
    ('x=1\n', 'E225'),                     # pycodestyle's whitespace rules (preview in ruff)
    ('import os\n', 'F401'),               # pyflakes
    ('def f(list):\n    return list\n', 'A002'),  # flake8-builtins
    ('x = dict(a=1)\n', 'C408'),           # flake8-comprehensions
    ('def f():\n    """Summary.\n    More."""\n', 'D205'),  # flake8-docstrings, pep257 convention
    ('x = 1\ndef f():\n    pass\n', 'E302'),
    ('x = 1  \n', 'W291'),
    ('def f(:\n', 'E999'),
])
def test_each_plugin_of_ament_flake8_has_its_rules_checked(tmp_path, monkeypatch, source, code):
    rc, errors = errors_in(tmp_path, monkeypatch, source)
    assert rc == 1
    assert any(f' {code} ' in error for error in errors), errors
    assert all(error.startswith('code.py:') for error in errors)


@pytest.mark.parametrize('source', [
    'def f():\n    """Summary."""\n',       # no docstring rule beyond pep257's: D100-D107 ignored
    'def f():\n    """Summary.\n\n    More.\n    """\n',  # D213 is ament_pep257's, not flake8's
    'x = 2*3\n',                            # E226, off by flake8's default
    'x = "it\'s"\n',                        # double quotes avoid an escape
])
def test_what_ament_flake8_leaves_out_passes(tmp_path, monkeypatch, source):
    assert errors_in(tmp_path, monkeypatch, source) == (0, [])


def test_lines_may_have_99_characters_unless_linelength_says_otherwise(tmp_path, monkeypatch):
    line = 'x = ' + repr('a' * 93) + '\n'
    assert len(line) == 100  # 99 characters and the newline
    assert errors_in(tmp_path, monkeypatch, line)[0] == 0
    rc, errors = errors_in(tmp_path, monkeypatch, line + 'y = 1' + ' ' * 95 + '# long\n')
    assert rc == 1
    assert [error.split()[1] for error in errors] == ['E501']
    assert errors_in(tmp_path, monkeypatch, line, '--linelength', '80')[0] == 1


def test_a_ruff_configuration_of_the_users_own_does_not_change_the_rules(tmp_path, monkeypatch):
    (tmp_path / 'pyproject.toml').write_text('[tool.ruff.lint]\nselect = ["ALL"]\n')
    assert errors_in(tmp_path, monkeypatch, TUTORIAL_NODE) == (0, [])


def test_excluded_files_are_not_checked(tmp_path, monkeypatch):
    (tmp_path / 'generated').mkdir()
    (tmp_path / 'generated' / 'bad.py').write_text('import os\n')
    assert errors_in(tmp_path, monkeypatch, 'x = 1\n', '--exclude', 'generated')[0] == 0
    assert errors_in(tmp_path, monkeypatch, 'x = 1\n')[0] == 1


def test_a_missing_path_is_one_clear_line(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main_with_errors(argv=['missing']) == (1, ['missing: no such file or directory'])
    assert capsys.readouterr().err == 'ament_flake8: missing: no such file or directory\n'
    assert main(argv=['missing']) == 1
