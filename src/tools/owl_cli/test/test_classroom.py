"""owl class serve's class list and hub configuration, without a hub (tests/test_class_server.py runs one)."""

from pathlib import Path

import pytest
from owl_cli.classroom.hub import Certificate, HubSettings, config_text
from owl_cli.classroom.students import Student, StudentsError, parse_students


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


def test_the_hub_configuration_lets_the_class_log_in_with_the_teacher_as_admin(tmp_path):
    settings = HubSettings(
        state=tmp_path, port=8443, hub_port=40001, proxy_api_port=40002,
        certificate=Certificate(tmp_path / 'hub.crt', tmp_path / 'hub.key', 'AB:CD'),
        students=['grace', 'ada1'], teacher='turing', venv=Path('/srv/venv'),
        proxy_command=['/usr/bin/node', '/srv/chp'])
    config: dict = {}

    class Section(dict):
        def __getattr__(self, name):
            return self.setdefault(name, Section())

        def __setattr__(self, name, value):
            self[name] = value

    exec(config_text(settings), {'get_config': lambda: config.setdefault('c', Section())})
    c = config['c']
    assert c['JupyterHub']['bind_url'] == 'https://:8443'
    assert c['JupyterHub']['authenticator_class'] == 'pam'
    assert c['Authenticator']['allowed_users'] == ['ada1', 'grace']
    assert c['Authenticator']['admin_users'] == ['turing']
    assert c['JupyterHub']['ssl_cert'] == str(tmp_path / 'hub.crt')
    assert c['Spawner']['cmd'] == ['/srv/venv/bin/jupyterhub-singleuser']
    assert c['ConfigurableHTTPProxy']['api_url'] == 'http://127.0.0.1:40002'
