"""The class server's JupyterHub: its own venv, its proxy, its certificate and its configuration.

Everything lives in a state folder only root can read (default STATE): `venv/` (JupyterHub, JupyterLab
and jupyter-server-proxy at the exact pins of config/classroom/requirements.txt, on the system's
python3, which every student account can run: the project's venv Python may sit in root's home),
`proxy/` (configurable-http-proxy from npm, pinned by config/classroom/package-lock.json, run by the
project venv's Node.js), the self-signed certificate when the teacher gives none, the hub's database
and cookie secret, and `jupyterhub_config.py`, written again at every start from the class list.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import ssl
import subprocess
import sys
from dataclasses import dataclass
from pathlib import Path

from owl_web.pages import FRONT_DOOR_PORT

from owl_cli.check.report import CLASS_RESULTS_VARIABLE
from owl_cli.classroom import (
    ClassError,
    files_digest,
    run_step,
    stamp_matches,
    teacher_page,
    worlds,
    write_stamp,
)
from owl_cli.classroom.lab import SYSTEM_PATH

STATE = Path('/var/lib/owl-kit-lab/class')
SYSTEM_PYTHON = '/usr/bin/python3'
CERTIFICATE_DAYS = 825  # the longest validity browsers accept for a certificate they are told to trust


def project_root() -> Path:
    """This checkout (env.sh sets OWL_ROOT)."""
    root = os.environ.get('OWL_ROOT')
    if not root:
        raise ClassError("OWL_ROOT is not set: run 'source env.sh' in the Owl Kit Lab folder first")
    return Path(root)


def ensure_venv(venv: Path) -> Path:
    """The hub's (and every server's) venv, made or brought to the pins when they changed; its folder."""
    pinned = project_root() / 'config' / 'classroom'
    digest = files_digest(pinned, ['requirements.txt'])
    if stamp_matches(venv, digest):
        return venv
    if not Path(SYSTEM_PYTHON).is_file():
        raise ClassError(f'{SYSTEM_PYTHON} is missing: the hub and every student need a Python all accounts '
                         "can run ('apt install python3')")
    print('owl class: installing JupyterHub into its own venv (once) ...', flush=True)
    uv = Path(sys.prefix) / 'bin' / 'uv'
    run_step([str(uv), 'venv', '--quiet', '--allow-existing', '--python', SYSTEM_PYTHON, str(venv)],
             'making the hub venv')
    run_step([str(uv), 'pip', 'install', '--quiet', '--python', str(venv / 'bin' / 'python'),
              '-r', str(pinned / 'requirements.txt')], 'installing the hub (uv pip install)')
    os.chmod(venv, 0o755)  # every student's server runs jupyterhub-singleuser from here
    write_stamp(venv, digest)
    return venv


def ensure_proxy(state: Path) -> list[str]:
    """The command that runs configurable-http-proxy, installed with npm ci when its lock changed."""
    pinned = project_root() / 'config' / 'classroom'
    inputs = ['package.json', 'package-lock.json']
    digest = files_digest(pinned, inputs)
    folder = state / 'proxy'
    script = folder / 'node_modules' / 'configurable-http-proxy' / 'bin' / 'configurable-http-proxy'
    node = Path(sys.prefix) / 'bin' / 'node'
    if not stamp_matches(folder, digest):
        print('owl class: installing configurable-http-proxy (once) ...', flush=True)
        folder.mkdir(parents=True, exist_ok=True)
        for name in inputs:
            shutil.copyfile(pinned / name, folder / name)
        npm = Path(sys.prefix) / 'bin' / 'npm'
        run_step([str(npm), 'ci', '--ignore-scripts', '--no-audit', '--no-fund', '--prefix', str(folder)],
                 'installing configurable-http-proxy (npm ci)')
        write_stamp(folder, digest)
    # node itself, not the wheel's Python launcher: a stopped launcher could leave the proxy on the port.
    found = subprocess.run([str(node), '-p', 'process.execPath'], capture_output=True, text=True, check=False)
    real_node = Path(found.stdout.strip() or node)
    return [str(real_node), str(script)]


@dataclass(frozen=True)
class Certificate:
    """The hub's certificate and key files, and the fingerprint students compare."""

    cert: Path
    key: Path
    fingerprint: str  # SHA-256, as browsers show it: colon-separated upper-case hex pairs


def fingerprint_of(cert: Path) -> str:
    """The SHA-256 fingerprint of a PEM certificate, as a browser shows it."""
    try:
        der = ssl.PEM_cert_to_DER_cert(cert.read_text())
    except (OSError, ValueError) as error:
        raise ClassError(f'cannot read the certificate {cert}: {error}') from None
    digest = hashlib.sha256(der).hexdigest().upper()
    return ':'.join(digest[i:i + 2] for i in range(0, len(digest), 2))


def teachers_certificate(cert: Path | None, key: Path | None) -> Certificate | None:
    """The certificate the teacher gave (--cert and --key), None for none; ClassError when it cannot serve."""
    if (cert is None) != (key is None):
        raise ClassError('give both --cert and --key, or neither (a self-signed certificate is made)')
    if cert is None or key is None:
        return None
    for option, path in (('--cert', cert), ('--key', key)):
        if not path.is_file():
            raise ClassError(f'{option} {path}: no such file')
    return Certificate(cert, key, fingerprint_of(cert))


def ensure_certificate(state: Path, cert: Path | None, key: Path | None, hostname: str) -> Certificate:
    """The teacher's certificate and key, or a self-signed one made at the first start and kept."""
    given = teachers_certificate(cert, key)
    if given is not None:
        return given
    cert, key = state / 'hub.crt', state / 'hub.key'
    if not (cert.is_file() and key.is_file()):
        run_step(['openssl', 'req', '-x509', '-newkey', 'ec', '-pkeyopt', 'ec_paramgen_curve:P-256',
                  '-nodes', '-days', str(CERTIFICATE_DAYS), '-subj', f'/CN={hostname}',
                  '-addext', f'subjectAltName=DNS:{hostname},DNS:localhost,IP:127.0.0.1',
                  '-keyout', str(key), '-out', str(cert)], 'making a self-signed certificate (openssl)')
        os.chmod(key, 0o600)
    return Certificate(cert, key, fingerprint_of(cert))


@dataclass(frozen=True)
class HubSettings:
    """What jupyterhub_config.py is written from."""

    state: Path
    port: int
    hub_port: int  # the hub's own API, on 127.0.0.1
    proxy_api_port: int  # configurable-http-proxy's API, on 127.0.0.1
    certificate: Certificate
    students: list[str]
    teacher: str
    venv: Path
    proxy_command: list[str]
    lab: Path  # the students' copy of this checkout (owl_cli.classroom.lab)
    domains: dict[str, int]  # each account's ROS domain (owl_cli.classroom.worlds)
    origins: list[str]  # what browsers show as the hub's origin: the pages behind its proxy trust them
    teacher_page_port: int  # the teacher's page (owl_cli.classroom.teacher_page), on 127.0.0.1


def config_text(settings: HubSettings) -> str:
    """jupyterhub_config.py for settings: PAM logins of the class's accounts, the teacher as admin."""
    values = {
        'JupyterHub.bind_url': f'https://:{settings.port}',
        'JupyterHub.hub_bind_url': f'http://127.0.0.1:{settings.hub_port}',
        'JupyterHub.ssl_cert': str(settings.certificate.cert),
        'JupyterHub.ssl_key': str(settings.certificate.key),
        'JupyterHub.db_url': f"sqlite:///{settings.state / 'jupyterhub.sqlite'}",
        'JupyterHub.cookie_secret_file': str(settings.state / 'jupyterhub_cookie_secret'),
        'JupyterHub.pid_file': str(settings.state / 'jupyterhub.pid'),
        'JupyterHub.cleanup_servers': True,  # Ctrl-C stops every student's server (their files stay)
        # Off: the check only logs, and its 60 s tick could fall within Ctrl-C's clean-up, after the
        # teacher's page stopped and before the students' servers did; JupyterHub then printed a
        # traceback (its check reads the stopped service's server, None by then).
        'JupyterHub.service_check_interval': 0,
        'JupyterHub.authenticator_class': 'pam',
        'Authenticator.allowed_users': sorted(settings.students),
        'Authenticator.admin_users': [settings.teacher],
        'Authenticator.allow_existing_users': False,  # the class list says who may log in
        'Spawner.cmd': [str(settings.venv / 'bin' / 'jupyterhub-singleuser')],
        'Spawner.default_url': '/lab',
        # Nothing of the teacher's shell (the checkout's venv, PYTHONPATH) reaches a student's server.
        'Spawner.env_keep': ['LANG', 'LC_ALL'],
        'ConfigurableHTTPProxy.command': settings.proxy_command,
        'ConfigurableHTTPProxy.api_url': f'http://127.0.0.1:{settings.proxy_api_port}',
    }
    # The teacher's page: a service the admin role may open and the default user role may not.
    values['JupyterHub.services'] = [{
        'name': teacher_page.SERVICE_NAME,
        'url': f'http://127.0.0.1:{settings.teacher_page_port}',
        'command': [str(settings.venv / 'bin' / 'python'), '-m', 'owl_cli.classroom.teacher_page',
                    str(settings.state)],
        'environment': {'PYTHONPATH': str(settings.lab / 'src' / 'tools' / 'owl_cli')},
        'oauth_no_confirm': True,
        'display': True,
    }]
    values['JupyterHub.load_roles'] = [{'name': 'owl-teacher-page', 'services': [teacher_page.SERVICE_NAME],
                                        'scopes': ['list:users', 'read:users:activity']}]
    lines = ['# Written by owl class serve at each start; edits here are lost.', 'c = get_config()  # noqa']
    for name, value in values.items():
        lines.append(f'c.{name} = {value!r}')
    fixed = {'PATH': SYSTEM_PATH, 'JUPYTER_CONFIG_PATH': str(settings.state / 'jupyter'),
             'ROS_AUTOMATIC_DISCOVERY_RANGE': 'LOCALHOST', 'OWL_TRUSTED_ORIGINS': ' '.join(settings.origins),
             'OWL_PAGE_PORT_FALLBACK': '1',  # classmates' pages hold the default ports: take a free one
             'OWL_PAGES_OWNER_ONLY': '1',  # and may not be reached by a classmate (owl_web.owner_only)
             CLASS_RESULTS_VARIABLE:  # each owl check's results to the teacher's page
                 f'http://127.0.0.1:{settings.teacher_page_port}/services/{teacher_page.SERVICE_NAME}/api/results'}
    lines += [
        '# Each account\'s own ROS domain and front door port (owl_cli.classroom.worlds).',
        f'domains = {settings.domains!r}',
        'c.Spawner.environment = {',
        *(f'    {name!r}: {value!r},' for name, value in fixed.items()),
        "    'ROS_DOMAIN_ID': lambda spawner: str(domains[spawner.user.name]),",
        f"    'OWL_FRONT_DOOR_PORT': lambda spawner: str({worlds.FRONT_DOOR_PORT_BASE} + "
        'domains[spawner.user.name]),',
        '}',
    ]
    return '\n'.join(lines) + '\n'


def server_config_text(lab: Path, terminal_rc: Path) -> str:
    """jupyter_server_config.py of every account's server: terminals in the lab, the front door's tile."""
    in_lab = f'. {lab}/env.sh >/dev/null && exec owl pages'
    shell = ['/bin/bash', '--rcfile', str(terminal_rc), '-i']
    front_door = {
        'command': ['/bin/bash', '-c', in_lab],  # starts the account's front door, which outlives it
        'timeout': 60,
        'new_browser_tab': True,
        'launcher_entry': {'title': 'Owl Kit Lab pages'},
    }
    return '\n'.join([
        '# Written by owl class; edits here are lost.',
        'import os',
        'c = get_config()  # noqa',
        '# A terminal is a shell of the lab, as `source env.sh` gives in a checkout.',
        f"c.ServerApp.terminado_settings = {{'shell_command': {shell!r}}}",
        '# The front door (every page of the account) through the server\'s proxy, at its own port.',
        f'front_door = {front_door!r}',
        f"front_door['port'] = int(os.environ.get('OWL_FRONT_DOOR_PORT', '{FRONT_DOOR_PORT}'))",
        "c.ServerProxy.servers = {'owl-kit-lab': front_door}",
        *PROXY_REPAIR,
    ]) + '\n'


# jupyter-server-proxy 4.6.0 passes on a page's WebSocket message that arrives after the browser
# closed its end (a student leaves the robot view while it streams), and tornado raises
# WebSocketClosedError from its callback: a traceback in the class server's log each time, for a
# message that has nowhere to go. The servers' configuration drops such a message quietly.
PROXY_REPAIR = (
    '# A page\'s message that arrives after the browser closed its WebSocket is dropped, not a traceback.',
    'from jupyter_server_proxy.handlers import ProxyHandler',
    'from tornado.websocket import WebSocketClosedError, WebSocketHandler',
    'def write_message_while_open(self, message, binary=False):',
    '    try:',
    '        return WebSocketHandler.write_message(self, message, binary)',
    '    except WebSocketClosedError:',
    '        return None',
    'ProxyHandler.write_message = write_message_while_open',
)


def terminal_rc_text(lab: Path) -> str:
    """The start-up file of a student's terminal: their own ~/.bashrc, then the lab's env.sh."""
    return ('# Written by owl class serve: a terminal of the class\'s Owl Kit Lab.\n'
            '[ -f ~/.bashrc ] && . ~/.bashrc\n'
            f'. {lab}/env.sh\n')


def write_server_config(folder: Path, lab: Path) -> None:
    """Write the servers' configuration folder (JUPYTER_CONFIG_PATH): lab terminals, the front door's tile."""
    folder.mkdir(mode=0o755, parents=True, exist_ok=True)
    os.chmod(folder, 0o755)  # every account's server reads it
    terminal_rc = folder / 'owl-terminal.bashrc'
    terminal_rc.write_text(terminal_rc_text(lab))
    (folder / 'jupyter_server_config.py').write_text(server_config_text(lab, terminal_rc))
    for written in (terminal_rc, folder / 'jupyter_server_config.py'):
        os.chmod(written, 0o644)


def write_config(settings: HubSettings) -> Path:
    """Write the hub's configuration and the servers' into the state folder; jupyterhub_config.py's path."""
    write_server_config(settings.state / 'jupyter', settings.lab)
    path = settings.state / 'jupyterhub_config.py'
    path.write_text(config_text(settings))
    return path
