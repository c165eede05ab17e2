"""scripts/direct_entry_scripts.py: the workspace's console scripts import their entry points directly."""

import subprocess
import sys
from pathlib import Path

import pytest
import setup_scripts

ROOT = Path(__file__).resolve().parents[1]
direct = setup_scripts.load('direct_entry_scripts')

# A plain Python process each (no ROS): no slot needed.
pytestmark = pytest.mark.no_processes


def setuptools_script(dist: str, name: str) -> str:
    """A console script as `setup.py develop` writes it (its lines that matter here)."""
    return (f'#!{sys.executable}\n'
            f"# EASY-INSTALL-ENTRY-SCRIPT: '{dist}','console_scripts','{name}'\n"
            'import re\nimport sys\n'
            'from importlib.metadata import distribution\n\n'
            "if __name__ == '__main__':\n"
            f"    sys.exit(load_entry_point('{dist}', 'console_scripts', '{name}')())\n")


def workspace(root: Path, entry_points: str) -> Path:
    """A built workspace with package my_pkg (dist my-pkg): its module, egg-info and script `greet`."""
    source = root / 'src' / 'my_pkg'
    (source / 'my_pkg').mkdir(parents=True)
    (source / 'my_pkg' / '__init__.py').write_text('')
    (source / 'my_pkg' / 'hello.py').write_text(
        'import sys\n\n\nclass Greeter:\n    @staticmethod\n    def run():\n'
        '        print("hi", sys.argv[1:])\n        return 3\n\n\n'
        'def main():\n    print("hello", sys.argv[1:])\n    return 4\n')
    egg_info = root / 'build' / 'my_pkg' / 'my_pkg.egg-info'
    egg_info.mkdir(parents=True)
    (egg_info / 'entry_points.txt').write_text(entry_points)
    script = root / 'install' / 'my_pkg' / 'lib' / 'my_pkg' / 'greet'
    script.parent.mkdir(parents=True)
    script.write_text(setuptools_script('my-pkg', 'greet'))
    script.chmod(0o755)
    return script


def run(script: Path, root: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(script), 'a', 'b'], capture_output=True, text=True,
                          env={'PYTHONPATH': str(root / 'src' / 'my_pkg')}, timeout=30)


def test_a_setuptools_script_calls_its_entry_point_directly_with_its_arguments_and_exit_code(tmp_path):
    script = workspace(tmp_path, '[console_scripts]\ngreet = my_pkg.hello:main\nother = my_pkg.x:y\n')
    assert direct.main([str(tmp_path)]) == 0
    text = script.read_text()
    assert text.startswith(f'#!{sys.executable}\n')
    assert 'importlib.metadata' not in text
    assert 'EASY-INSTALL' not in text
    assert 'from my_pkg.hello import main' in text
    ran = run(script, tmp_path)
    assert (ran.returncode, ran.stdout) == (4, "hello ['a', 'b']\n"), ran.stderr
    assert direct.main([str(tmp_path)]) == 0  # once rewritten, left as it is
    assert script.read_text() == text


def test_a_dotted_entry_point_is_called_through_its_object(tmp_path):
    script = workspace(tmp_path, '[console_scripts]\ngreet = my_pkg.hello:Greeter.run [extra]\n')
    direct.main([str(tmp_path)])
    ran = run(script, tmp_path)
    assert (ran.returncode, ran.stdout) == (3, "hi ['a', 'b']\n"), ran.stderr


@pytest.mark.parametrize('entry_points', [
    '[console_scripts]\nother = my_pkg.hello:main\n',   # not declared
    '[gui_scripts]\ngreet = my_pkg.hello:main\n',       # not in its group
    '[console_scripts]\ngreet = my_pkg.hello\n',        # no attribute
    'greet = my_pkg.hello:main\n',                      # no section: not an ini file
])
def test_an_entry_point_it_cannot_find_leaves_the_script_working_and_says_so(tmp_path, capsys, entry_points):
    script = workspace(tmp_path, entry_points)
    before = script.read_text()
    assert direct.main([str(tmp_path)]) == 0
    assert script.read_text() == before
    error = capsys.readouterr().err
    assert error.startswith(f'setup: {script} left as setuptools wrote it: ')
    assert error.count('\n') == 1


def test_a_script_of_another_kind_is_left_alone(tmp_path):
    script = workspace(tmp_path, '[console_scripts]\ngreet = my_pkg.hello:main\n')
    own = f'#!{sys.executable}\nfrom my_pkg.hello import main\n\nmain()\n'
    script.write_text(own)
    (script.parent / 'data.bin').write_bytes(b'\xff\xfe\0')
    assert direct.main([str(tmp_path)]) == 0
    assert script.read_text() == own


@pytest.mark.parametrize('argv', [[], ['a', 'b'], ['/no/such/workspace']])
def test_wrong_arguments_are_one_usage_line(argv, capsys):
    assert direct.main(argv) == 2
    assert capsys.readouterr().err.startswith('usage: direct_entry_scripts.py WORKSPACE')


def test_setup_left_no_console_script_of_this_workspace_looking_its_entry_point_up():
    installed = [path for pattern in ('install/*/lib/*/*', 'install/*/bin/*') for path in ROOT.glob(pattern)
                 if path.is_file()]
    assert any('from olive_sim.servo_node import main' in path.read_text(errors='replace')
               for path in installed)
    slow = [str(path) for path in installed if direct.MARKER in path.read_text(errors='replace')]
    assert not slow, f'make setup left these as setuptools wrote them: {slow}'
