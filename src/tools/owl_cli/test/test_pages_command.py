"""`owl pages`: the front door's address and every page, and one line for what it cannot do."""

import os
import re
import stat

import pytest
from owl_cli.main import main
from owl_web import pages


@pytest.fixture
def folder(tmp_path, monkeypatch):
    path = tmp_path / 'pages'
    monkeypatch.setenv('OWL_PAGES_DIR', str(path))
    monkeypatch.setenv('OWL_FRONT_DOOR_PORT', '0')
    monkeypatch.delenv('OWL_FRONT_DOOR', raising=False)
    monkeypatch.delenv('OWL_TRUSTED_ORIGINS', raising=False)
    yield path
    pages.stop_front_door(path)


def test_owl_pages_starts_the_front_door_and_lists_every_page_with_how_to_start_it(folder, capsys):
    assert main(['pages']) == 0
    lines = capsys.readouterr().out.splitlines()
    door = re.match(r"owl pages: the front door: (http://127\.0\.0\.1:\d+/) \(every running page is there; "
                    r"Ctrl-C does not stop it: 'owl pages --stop'\)$", lines[0])
    assert door, lines
    assert pages.front_door_record(folder).url == door.group(1)
    assert lines[1].split() == ['PAGE', 'STATE', 'OPEN', 'OWN', 'ADDRESS,', 'OR', 'HOW', 'TO', 'START', 'IT']
    assert re.match(r'rqt +not running +- +rqt$', lines[3])
    assert lines[5].endswith('ros2 launch olive_sim owl_kit.launch.py (module 10.42.0.20)')
    assert len(lines) == 9  # the three tools' pages and the four modules'
    assert main(['pages']) == 0  # a second call finds the same front door
    assert door.group(1) in capsys.readouterr().out.splitlines()[0]
    assert main(['pages', '--stop']) == 0
    assert capsys.readouterr().out == 'owl pages: the front door stopped\n'


@pytest.mark.parametrize(('variable', 'value', 'line'), [
    ('OWL_FRONT_DOOR_PORT', 'eighty',
     "owl pages: OWL_FRONT_DOOR_PORT must be a port number 0..65535, got 'eighty'"),
    ('OWL_TRUSTED_ORIGINS', 'hub.example.edu', "owl pages: OWL_TRUSTED_ORIGINS: 'hub.example.edu' is not an "
                                               'origin such as https://hub.example.edu or http://lab.local:8000'),
])
def test_bad_settings_get_one_line_and_start_nothing(folder, monkeypatch, capsys, variable, value, line):
    monkeypatch.setenv(variable, value)
    assert main(['pages']) == 1
    assert capsys.readouterr().out.splitlines() == [line]
    assert pages.front_door_record(folder) is None


def test_a_pages_folder_that_is_not_private_is_refused(folder, capsys):
    folder.mkdir(mode=0o777)
    os.chmod(folder, 0o777)
    assert main(['pages']) == 1
    assert capsys.readouterr().out == (f'owl pages: the pages folder {folder} is not a private folder of '
                                       'yours (mode 0700); remove it, or choose another with OWL_PAGES_DIR\n')
    assert stat.S_IMODE(folder.stat().st_mode) == 0o777
    assert main(['pages', '--stop']) == 0
    assert capsys.readouterr().out == 'owl pages: no front door runs\n'


def test_without_a_front_door_each_page_keeps_its_own_address(folder, monkeypatch, capsys):
    monkeypatch.setenv('OWL_FRONT_DOOR', 'off')
    assert main(['pages']) == 0
    assert capsys.readouterr().out.splitlines()[0] == \
        'owl pages: no front door (OWL_FRONT_DOOR=off): each page is at its own address'
    assert pages.front_door_record(folder) is None
