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

from owl_cli.classroom import ClassError, run_step

STATE = Path('/var/lib/owl-kit-lab/class')
SYSTEM_PYTHON = '/usr/bin/python3'
CERTIFICATE_DAYS = 825  # the longest validity browsers accept for a certificate they are told to trust


def project_root() -> Path:
    """This checkout (env.sh sets OWL_ROOT)."""
    root = os.environ.get('OWL_ROOT')
    if not root:
        raise ClassError("OWL_ROOT is not set: run 'source env.sh' in the Owl Kit Lab folder first")
    return Path(root)


def stamp_matches(folder: Path, inputs: list[Path]) -> bool:
    """Whether folder was made from inputs as they are now (its .owl-inputs.sha256 says so)."""
    stamp = folder / '.owl-inputs.sha256'
    return stamp.is_file() and stamp.read_text() == inputs_digest(inputs)


def inputs_digest(inputs: list[Path]) -> str:
    """One SHA-256 over the files' contents, in order."""
    digest = hashlib.sha256()
    for path in inputs:
        digest.update(path.read_bytes())
    return digest.hexdigest()


def ensure_venv(state: Path) -> Path:
    """The hub's venv, made or brought to the pins when they changed; its folder."""
    requirements = project_root() / 'config' / 'classroom' / 'requirements.txt'
    venv = state / 'venv'
    if stamp_matches(venv, [requirements]):
        return venv
    if not Path(SYSTEM_PYTHON).is_file():
        raise ClassError(f'{SYSTEM_PYTHON} is missing: the hub and every student need a Python all accounts '
                         "can run ('apt install python3')")
    print('owl class: installing JupyterHub into its own venv (once) ...', flush=True)
    uv = Path(sys.prefix) / 'bin' / 'uv'
    run_step([str(uv), 'venv', '--quiet', '--allow-existing', '--python', SYSTEM_PYTHON, str(venv)],
             'making the hub venv')
    run_step([str(uv), 'pip', 'install', '--quiet', '--python', str(venv / 'bin' / 'python'),
              '-r', str(requirements)], 'installing the hub (uv pip install)')
    os.chmod(venv, 0o755)  # every student's server runs jupyterhub-singleuser from here
    (venv / '.owl-inputs.sha256').write_text(inputs_digest([requirements]))
    return venv


def ensure_proxy(state: Path) -> list[str]:
    """The command that runs configurable-http-proxy, installed with npm ci when its lock changed."""
    pinned = project_root() / 'config' / 'classroom'
    inputs = [pinned / 'package.json', pinned / 'package-lock.json']
    folder = state / 'proxy'
    script = folder / 'node_modules' / 'configurable-http-proxy' / 'bin' / 'configurable-http-proxy'
    node = Path(sys.prefix) / 'bin' / 'node'
    if not stamp_matches(folder, inputs):
        print('owl class: installing configurable-http-proxy (once) ...', flush=True)
        folder.mkdir(parents=True, exist_ok=True)
        for path in inputs:
            shutil.copyfile(path, folder / path.name)
        npm = Path(sys.prefix) / 'bin' / 'npm'
        run_step([str(npm), 'ci', '--ignore-scripts', '--no-audit', '--no-fund', '--prefix', str(folder)],
                 'installing configurable-http-proxy (npm ci)')
        (folder / '.owl-inputs.sha256').write_text(inputs_digest(inputs))
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


def ensure_certificate(state: Path, cert: Path | None, key: Path | None, hostname: str) -> Certificate:
    """The teacher's certificate and key, or a self-signed one made at the first start and kept."""
    if (cert is None) != (key is None):
        raise ClassError('give both --cert and --key, or neither (a self-signed certificate is made)')
    if cert is not None and key is not None:
        for path in (cert, key):
            if not path.is_file():
                raise ClassError(f'no such file: {path}')
        return Certificate(cert, key, fingerprint_of(cert))
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
        'JupyterHub.authenticator_class': 'pam',
        'Authenticator.allowed_users': sorted(settings.students),
        'Authenticator.admin_users': [settings.teacher],
        'Authenticator.allow_existing_users': False,  # the class list says who may log in
        'Spawner.cmd': [str(settings.venv / 'bin' / 'jupyterhub-singleuser')],
        'Spawner.default_url': '/lab',
        'ConfigurableHTTPProxy.command': settings.proxy_command,
        'ConfigurableHTTPProxy.api_url': f'http://127.0.0.1:{settings.proxy_api_port}',
    }
    lines = ['# Written by owl class serve at each start; edits here are lost.', 'c = get_config()  # noqa']
    for name, value in values.items():
        lines.append(f'c.{name} = {value!r}')
    return '\n'.join(lines) + '\n'


def write_config(settings: HubSettings) -> Path:
    """Write jupyterhub_config.py into the state folder; its path."""
    path = settings.state / 'jupyterhub_config.py'
    path.write_text(config_text(settings))
    return path
