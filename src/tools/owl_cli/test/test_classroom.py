"""owl class serve's class list and hub configuration, without a hub (tests/test_class_server.py runs one)."""

import json
import re
import subprocess
import sys
from pathlib import Path
from types import SimpleNamespace

import pytest
from owl_cli.classroom import ClassError
from owl_cli.classroom.hub import Certificate, HubSettings, config_text, server_config_text, terminal_rc_text
from owl_cli.classroom.lab import bootstrap_environment, checkout_files, copy_files
from owl_cli.classroom.students import Student, StudentsError, parse_students
from owl_cli.classroom.teacher_page import (
    Roll,
    age,
    class_results,
    page_html,
    parse_results,
    sections_of,
    store_results,
    table_html,
)
from owl_cli.classroom.teacher_page import main as teacher_page_main
from owl_cli.classroom.worlds import assign_domains, read_domains, record_domains


def test_a_class_list_gives_its_students_in_order_skipping_blank_and_comment_lines():
    text = '# class 4b\n\nada1 first-secret\n  grace secret2  \n'
    assert parse_students(text, 'class.txt') == [Student('ada1', 'first-secret'), Student('grace', 'secret2')]


@pytest.mark.parametrize(('text', 'message'), [
    ('ada1 x\nAda2 y\n', "class.txt, line 2: 'Ada2' is not a name of a lowercase letter, then lowercase "
                         'letters and digits, at most 32'),
    ('1ada x\n', "class.txt, line 1: '1ada' is not a name of"),
    ('ada-b x\n', "class.txt, line 1: 'ada-b' is not a name of"),
    ('a' * 33 + ' x\n', 'class.txt, line 1: '),
    ('ada1 x\ngrace y\nada1 z\n', "class.txt, line 3: 'ada1' is listed twice"),
    ('ada1\n', 'class.txt, line 1: expected "name password", got 1 field(s)'),
    ('ada1 two words\n', 'class.txt, line 1: expected "name password", got 3 field(s)'),
    ('# nobody yet\n\n', 'class.txt: no student (one per line: name password)'),
])
def test_a_wrong_line_is_named_in_one_line(text, message):
    with pytest.raises(StudentsError) as raised:
        parse_students(text, 'class.txt')
    assert str(raised.value).startswith(message)
    assert '\n' not in str(raised.value)


class Section(dict):
    """A traitlets Config as a configuration file sees it: sections made on first use."""

    def __getattr__(self, name):
        return self.setdefault(name, Section())

    def __setattr__(self, name, value):
        self[name] = value


def read_config(text: str) -> Section:
    """What a Jupyter configuration file sets."""
    config = Section()
    exec(text, {'get_config': lambda: config})
    return config


def test_the_hub_configuration_lets_the_class_log_in_with_the_teacher_as_admin(tmp_path):
    settings = HubSettings(
        state=tmp_path, port=8443, hub_port=40001, proxy_api_port=40002,
        certificate=Certificate(tmp_path / 'hub.crt', tmp_path / 'hub.key', 'AB:CD'),
        students=['grace', 'ada1'], teacher='turing', venv=Path('/srv/venv'),
        proxy_command=['/usr/bin/node', '/srv/chp'], lab=Path('/srv/lab'),
        domains={'grace': 1, 'ada1': 2, 'turing': 3}, origins=['https://hub.example.edu:8443'],
        teacher_page_port=40003)
    c = read_config(config_text(settings))
    assert c['JupyterHub']['bind_url'] == 'https://:8443'
    assert c['JupyterHub']['authenticator_class'] == 'pam'
    assert c['Authenticator']['allowed_users'] == ['ada1', 'grace']
    assert c['Authenticator']['admin_users'] == ['turing']
    assert c['JupyterHub']['ssl_cert'] == str(tmp_path / 'hub.crt')
    assert c['Spawner']['cmd'] == ['/srv/venv/bin/jupyterhub-singleuser']
    assert c['ConfigurableHTTPProxy']['api_url'] == 'http://127.0.0.1:40002'
    environment = c['Spawner']['environment']
    student = SimpleNamespace(user=SimpleNamespace(name='ada1'))
    assert environment['ROS_DOMAIN_ID'](student) == '2'  # each account's own ROS world
    assert environment['OWL_FRONT_DOOR_PORT'](student) == '7002'
    assert environment['ROS_AUTOMATIC_DISCOVERY_RANGE'] == 'LOCALHOST'
    assert environment['OWL_PAGE_PORT_FALLBACK'] == '1'  # each student's robot view, not only the first's
    assert environment['OWL_PAGES_OWNER_ONLY'] == '1'  # and nobody else's
    assert environment['OWL_TRUSTED_ORIGINS'] == 'https://hub.example.edu:8443'
    assert environment['JUPYTER_CONFIG_PATH'] == str(tmp_path / 'jupyter')
    assert 'PYTHONPATH' not in c['Spawner']['env_keep']
    assert 'PATH' not in c['Spawner']['env_keep']
    [page] = c['JupyterHub']['services']
    assert page['url'] == 'http://127.0.0.1:40003'
    assert page['command'][1:] == ['-m', 'owl_cli.classroom.teacher_page', str(tmp_path)]
    assert page['environment'] == {'PYTHONPATH': '/srv/lab/src/tools/owl_cli'}  # the lab's copy of owl_cli
    [role] = c['JupyterHub']['load_roles']  # the page may list the users; who may open it is the hub's rule
    assert role['services'] == [page['name']]
    assert role['scopes'] == ['list:users', 'read:users:activity']
    # JupyterHub's service check, which could run amid Ctrl-C's clean-up and print a traceback, is off
    assert c['JupyterHub']['service_check_interval'] == 0


class WebSocketClosedError(Exception):
    """tornado.websocket's, in the stand-ins below."""


class WebSocketHandler:
    """tornado's WebSocketHandler as jupyter-server-proxy uses it: a write to a closed socket raises."""

    def __init__(self) -> None:
        self.sent: list[str] = []
        self.closed = False

    def write_message(self, message: str, binary: bool = False) -> None:
        if self.closed:
            raise WebSocketClosedError()
        self.sent.append(message)


class ProxyHandler(WebSocketHandler):
    """jupyter_server_proxy.handlers.ProxyHandler's stand-in."""


@pytest.fixture
def server_modules(monkeypatch):
    """Stand-ins for the servers' venv's tornado and jupyter-server-proxy (this venv has neither)."""
    for name, module in (('tornado.websocket', SimpleNamespace(WebSocketClosedError=WebSocketClosedError,
                                                               WebSocketHandler=WebSocketHandler)),
                         ('jupyter_server_proxy.handlers', SimpleNamespace(ProxyHandler=ProxyHandler))):
        monkeypatch.setitem(sys.modules, name, module)
    monkeypatch.setattr(ProxyHandler, 'write_message', WebSocketHandler.write_message)


def test_a_pages_message_after_the_browser_closed_its_socket_is_dropped_quietly(server_modules):
    read_config(server_config_text(Path('/srv/lab'), Path('/rc')))
    handler = ProxyHandler()
    handler.write_message('first')
    handler.closed = True
    assert handler.write_message('late') is None  # upstream: WebSocketClosedError, a logged traceback
    assert handler.sent == ['first']


def test_a_students_server_opens_terminals_in_the_lab_and_a_tile_for_their_front_door(
        monkeypatch, server_modules):
    monkeypatch.delenv('OWL_FRONT_DOOR_PORT', raising=False)
    assert read_config(server_config_text(Path('/srv/lab'), Path('/rc')))['ServerProxy']['servers'][
        'owl-kit-lab']['port'] == 8090  # a pod of its own (Kubernetes): the front door's own port
    monkeypatch.setenv('OWL_FRONT_DOOR_PORT', '7002')
    c = read_config(server_config_text(Path('/srv/lab'), Path('/srv/jupyter/terminal.bashrc')))
    assert c['ServerApp']['terminado_settings']['shell_command'] == [
        '/bin/bash', '--rcfile', '/srv/jupyter/terminal.bashrc', '-i']
    front_door = c['ServerProxy']['servers']['owl-kit-lab']
    assert front_door['port'] == 7002
    assert front_door['command'] == ['/bin/bash', '-c', '. /srv/lab/env.sh >/dev/null && exec owl pages']
    assert front_door['launcher_entry']['title'] == 'Owl Kit Lab pages'
    assert terminal_rc_text(Path('/srv/lab')).splitlines()[1:] == ['[ -f ~/.bashrc ] && . ~/.bashrc',
                                                                   '. /srv/lab/env.sh']


def test_each_account_keeps_its_domain_and_a_newcomer_takes_the_lowest_free_one():
    known = {'ada1': 1, 'grace': 2, 'left': 3}
    assert assign_domains(known, ['grace', 'new1', 'ada1', 'new2'], taken=[4]) == {
        'grace': 2, 'ada1': 1, 'new1': 5, 'new2': 6}  # 3 stays the one who left's, 4 is another's


def test_a_class_larger_than_the_domains_is_one_line():
    with pytest.raises(ClassError) as raised:
        assign_domains({}, [f's{i}' for i in range(102)])
    assert str(raised.value) == ('no ROS domain left for s101: a class server holds at most 101 accounts '
                                 '(domains 1-101)')


def test_the_domains_record_is_kept_and_a_broken_one_is_one_line(tmp_path):
    assert read_domains(tmp_path) == {}
    record_domains(tmp_path, {'ada1': 1}, {'grace': 2})
    assert read_domains(tmp_path) == {'ada1': 1, 'grace': 2}
    for broken in ('{"ada1": 500}', '[1, 2]', '{not json'):
        (tmp_path / 'ros-domains.json').write_text(broken)
        with pytest.raises(ClassError) as raised:
            read_domains(tmp_path)
        assert 'ros-domains.json' in str(raised.value)
        assert '\n' not in str(raised.value)


def git(folder: Path, *args: str) -> None:
    subprocess.run(['git', '-C', str(folder), *args], check=True, capture_output=True)


def test_the_lab_copies_what_git_tracks_or_would_and_drops_what_the_checkout_lost(tmp_path):
    checkout, lab = tmp_path / 'checkout', tmp_path / 'lab'
    (checkout / 'src').mkdir(parents=True)
    lab.mkdir()
    git(checkout, 'init', '-q')
    (checkout / '.gitignore').write_text('/.venv/\n')
    (checkout / 'src' / 'node.py').write_text('tracked')
    (checkout / 'gone.py').write_text('tracked, then deleted')
    git(checkout, 'add', '.')
    (checkout / 'new.py').write_text('not yet added')
    (checkout / '.venv').mkdir()
    (checkout / '.venv' / 'python').write_text('ignored')
    copy_files(checkout, lab, checkout_files(checkout))
    assert (lab / 'gone.py').is_file()
    (checkout / 'gone.py').unlink()
    names = checkout_files(checkout)
    assert names == ['.gitignore', 'new.py', 'src/node.py']
    copy_files(checkout, lab, names)
    assert not (lab / 'gone.py').exists()
    assert (lab / 'src' / 'node.py').read_text() == 'tracked'
    assert not (lab / '.venv').exists()


def test_a_checkout_that_is_not_a_git_one_is_one_line(tmp_path):
    with pytest.raises(ClassError) as raised:
        checkout_files(tmp_path)
    assert str(raised.value).startswith(f'{tmp_path} is not a git checkout')


def test_the_labs_bootstrap_runs_without_what_env_sh_added_and_with_the_rest():
    shell = {'PATH': '/root/owl/.venv/bin:/usr/bin', 'VIRTUAL_ENV': '/root/owl/.venv',
             'OWL_ROOT': '/root/owl', 'PYTHONPATH': '/root/owl/install/lib',
             'AMENT_PREFIX_PATH': '/root/owl/.venv', 'ROS_DOMAIN_ID': '3',
             'SSL_CERT_FILE': '/etc/ssl/certs/ca.crt', 'https_proxy': 'http://proxy:3128', 'HOME': '/root'}
    assert bootstrap_environment(shell, '/usr/bin/python3') == {
        'PATH': '/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin', 'PYTHON': '/usr/bin/python3',
        'SSL_CERT_FILE': '/etc/ssl/certs/ca.crt', 'https_proxy': 'http://proxy:3128', 'HOME': '/root'}


def test_the_teachers_page_shows_each_students_latest_results_by_section_and_when_they_last_worked():
    roll = Roll(['ada1', 'grace', 'alan'], sections_of([('keyboard', '3.4'), ('imu_turtle', '4.3'),
                                                         ('imu_plot', '4.3')]))
    assert roll.sections == [('3.4', ['keyboard']), ('4.3', ['imu_turtle', 'imu_plot'])]
    results = {'ada1': {'imu_turtle': {'passed': True, 'at': 1000.0},
                        'imu_plot': {'passed': False, 'at': 900.0}},
               'grace': {'keyboard': {'passed': False, 'at': 400.0}}}
    table = table_html(roll, results, {'grace': 1100.0}, now=1200.0)
    rows = dict(re.findall(r'<tr data-student="(\w+)">(.*?)</tr>', table))
    assert list(rows) == ['ada1', 'grace', 'alan']  # the class list's order
    heads = re.findall(r'<th scope="col">([^<]+)</th>', table)
    assert heads == ['student', 'last worked', 'exercises', '3.4', '4.3']
    assert '<td class="sum">1 of 3 passed, 1 failed</td>' in rows['ada1']  # before the sections
    assert '<td class="sum">0 of 3 passed</td>' in rows['alan']
    assert 'class="passed" data-exercise="imu_turtle"' in rows['ada1']
    assert 'class="failed" data-exercise="imu_plot"' in rows['ada1']
    assert 'class="not-run" data-exercise="keyboard"' in rows['ada1']
    assert '<td class="last">3 min ago</td>' in rows['ada1']  # the latest check
    assert '<td class="last">1 min ago</td>' in rows['grace']  # the hub saw grace after her check
    assert '<td class="last">never</td>' in rows['alan']
    assert 'href="../../user/grace/lab"' in rows['grace']  # the admin opens her JupyterLab
    page = page_html(table, 'token"<')
    assert table in page
    assert '<meta name="xsrf-token" content="token&quot;&lt;">' in page  # the refreshes send it


def test_the_class_roll_round_trips_and_the_page_refuses_a_broken_one_in_one_line(tmp_path, capsys):
    roll = Roll(['ada1'], [('4.3', ['imu_turtle'])])
    assert Roll.from_json(roll.to_json()) == roll
    (tmp_path / 'class-roll.json').write_text('{"students": 3}')
    assert teacher_page_main([str(tmp_path)]) == 2
    [line] = capsys.readouterr().err.splitlines()
    assert line.startswith(f"teacher page: cannot read the class roll {tmp_path / 'class-roll.json'}: ")
    assert teacher_page_main([]) == 2


@pytest.mark.parametrize(('seconds', 'text'), [(5, 'just now'), (125, '2 min ago'), (7300, '2 h ago'),
                                               (3 * 86400 + 5, '3 days ago')])
def test_ages_read_as_a_teacher_says_them(seconds, text):
    assert age(seconds) == text


def test_the_teachers_page_keeps_what_a_students_owl_check_sends_and_refuses_what_is_not_results(tmp_path):
    sent = {'exercises': {'imu_turtle': {'passed': True, 'failed': 0, 'criteria': 3, 'section': '4.3',
                                         'at': 5.0, 'workspace': '/home/ada1/ros2_ws', 'error': ''},
                          'not_an_exercise': {'passed': True}}}
    kept = parse_results(json.dumps(sent).encode(), ['imu_turtle', 'keyboard'])
    assert kept == {'imu_turtle': {'passed': True, 'failed': 0, 'criteria': 3, 'section': '4.3', 'at': 5.0}}
    store = tmp_path / 'check-results'
    store_results(store, 'ada1', kept)
    roll = Roll(['ada1', 'grace'], [('4.3', ['imu_turtle'])])
    assert class_results(roll, store) == {'ada1': kept, 'grace': {}}
    for body, reason in [(b'not json', 'results must be JSON'), (b'[1]', 'results must be {"exercises"'),
                         (b'{"exercises": {"imu_turtle": {"passed": "yes"}}}',
                          'imu_turtle: a result needs "passed": true or false'),
                         (b' ' * (300 * 1024), 'results over 256 KiB')]:
        with pytest.raises(ValueError, match=re.escape(reason)):
            parse_results(body, ['imu_turtle'])
    assert class_results(roll, store)['ada1'] == kept  # a refused message changes nothing
