"""owl class serve: start the class server (JupyterHub) for the students of a class list.

Run as root on the teacher's Linux machine. Each student of FILE (`name password` per line) and
the teacher get a Unix account with a private home, made now or kept from an earlier start (with
the password FILE gives; the teacher's from OWL_CLASS_TEACHER_PASSWORD or a prompt). The hub
serves HTTPS on the port printed, with the teacher's certificate (--cert/--key) or a self-signed
one whose fingerprint is printed for the students to compare. Each account's server runs the
students' lab (a copy of this checkout every account can run) in a ROS domain of its own, with a
terminal of the lab and a launcher tile for its front door. Ctrl-C stops the hub, every student's
server and whatever they still run; their homes stay.
"""

from __future__ import annotations

import argparse
import getpass
import os
import signal
import socket
import subprocess
import sys
from pathlib import Path

from owl_cli.check import catalogue
from owl_cli.classroom import ClassError, accounts, closed_parent, hub, teacher_page, worlds
from owl_cli.classroom.lab import ensure_lab
from owl_cli.classroom.students import StudentsError, name_problem, parse_students

DEFAULT_PORT = 8443
HUB_STOP_TIMEOUT = 30.0  # s for the hub to stop its servers and itself after Ctrl-C
PASSWORD_VARIABLE = 'OWL_CLASS_TEACHER_PASSWORD'


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of `owl class serve`."""
    parser.add_argument('--students', required=True, metavar='FILE',
                        help='the class list: one student per line, "name password"')
    parser.add_argument('--teacher', required=True, metavar='NAME',
                        help=f'the teacher\'s account (password from ${PASSWORD_VARIABLE}, else asked)')
    parser.add_argument('--port', type=int, default=DEFAULT_PORT,
                        help=f'the HTTPS port on every interface (default {DEFAULT_PORT})')
    parser.add_argument('--cert', type=Path, help='the certificate (PEM) the hub shows; with --key')
    parser.add_argument('--key', type=Path, help="the certificate's private key (PEM)")
    parser.add_argument('--state', type=Path, default=hub.STATE,
                        help=f'where the hub keeps its venv, database and certificate (default {hub.STATE})')
    parser.add_argument('--lab', type=Path,
                        help="where the students' copy of this checkout is built (default STATE/lab; "
                             'classes may share one)')


def free_local_port() -> int:
    """A port on 127.0.0.1 free now (for the hub's and the proxy's own APIs)."""
    with socket.socket() as probe:
        probe.bind(('127.0.0.1', 0))
        return int(probe.getsockname()[1])


def teacher_password() -> str:
    """The teacher's password from the environment, else asked in the terminal."""
    password = os.environ.get(PASSWORD_VARIABLE)
    if password is None:
        if not sys.stdin.isatty():
            raise ClassError(f"set {PASSWORD_VARIABLE} or run it in a terminal to be asked the teacher's "
                             'password')
        password = getpass.getpass("The teacher's password: ")
    if not password or any(character.isspace() for character in password):
        raise ClassError("the teacher's password must be non-empty, without spaces")
    return password


def prepare(args: argparse.Namespace) -> hub.HubSettings:
    """Check everything, then make the accounts and the hub's files: the hub's settings."""
    if os.geteuid() != 0:
        raise ClassError('run it as root (sudo): it makes a Unix account for each student')
    if not 0 < args.port < 65536:
        raise ClassError(f'--port must be 1-65535, got {args.port}')
    with socket.socket() as probe:  # the hub would fail later, amid its own log lines
        probe.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)  # as the proxy binds: past TIME_WAIT
        try:
            probe.bind(('', args.port))
        except OSError as error:
            raise ClassError(f'--port {args.port}: {error.strerror or error}') from None
    hub.teachers_certificate(args.cert, args.key)  # a wrong one is said before anything is made
    try:
        text = Path(args.students).read_text()
    except (OSError, UnicodeDecodeError) as error:
        raise ClassError(f'cannot read the class list {args.students}: {error}') from None
    students = parse_students(text, args.students)
    problem = name_problem(args.teacher)
    if problem:
        raise ClassError(f'--teacher: {problem}')
    if args.teacher in {s.name for s in students}:
        raise ClassError(f"--teacher: '{args.teacher}' is also in the class list")
    conflicts = [c for c in [accounts.conflict(s.name, accounts.STUDENTS) for s in students]
                 + [accounts.conflict(args.teacher, accounts.TEACHERS)] if c]
    if conflicts:
        raise ClassError(conflicts[0])
    lab_folder = args.lab or args.state / 'lab'
    for option, folder in (('--state', args.state), ('--lab', lab_folder)):
        closed = closed_parent(folder)
        if closed is not None:
            raise ClassError(f'{option} {folder}: every student runs what is inside, but {closed} is '
                             'closed to other accounts (it needs o+x)')
    password = teacher_password()
    args.state.mkdir(mode=0o700, parents=True, exist_ok=True)
    os.chmod(args.state, 0o711)  # students' servers run the venv inside; the rest stays root's
    certificate = hub.ensure_certificate(args.state, args.cert, args.key, socket.gethostname())
    venv = hub.ensure_venv(args.state / 'venv')
    proxy_command = hub.ensure_proxy(args.state)
    lab = ensure_lab(lab_folder, hub.project_root(), hub.SYSTEM_PYTHON)
    known = worlds.read_domains(args.state)
    names = [s.name for s in students] + [args.teacher]
    domains = worlds.record_domains(args.state, known,
                                    worlds.assign_domains(known, names, worlds.held_domains()))
    roll = teacher_page.Roll([s.name for s in students],
                             teacher_page.sections_of([(e.id, e.section) for e in catalogue.CHECKABLE]))
    (args.state / teacher_page.ROLL).write_text(roll.to_json())
    for group in (accounts.STUDENTS, accounts.TEACHERS):
        accounts.ensure_group(group)
    made = [s.name for s in students if accounts.ensure_account(s.name, s.password, accounts.STUDENTS)]
    accounts.ensure_account(args.teacher, password, accounts.TEACHERS)
    print(f'owl class: {len(students)} students ({len(made)} new accounts), teacher {args.teacher}',
          flush=True)
    return hub.HubSettings(args.state, args.port, free_local_port(), free_local_port(), certificate,
                           [s.name for s in students], args.teacher, venv, proxy_command, lab,
                           {name: domains[name] for name in names}, hub_origins(args.port), free_local_port())


def hub_origins(port: int) -> list[str]:
    """The origins a browser may show for the hub: this machine's names and addresses at port.

    Names the machine does not know of itself (a DNS alias) come from OWL_TRUSTED_ORIGINS.
    """
    hosts = {socket.gethostname(), socket.getfqdn(), 'localhost', '127.0.0.1'}
    try:
        listed = subprocess.run(['hostname', '-I'], capture_output=True, text=True, check=False).stdout
    except FileNotFoundError:
        listed = ''
    hosts |= {f'[{address}]' if ':' in address else address for address in listed.split()}
    extra = os.environ.get('OWL_TRUSTED_ORIGINS', '').replace(',', ' ').split()
    return sorted({f'https://{host}:{port}' for host in hosts} | set(extra))


def interrupt(signum: int, frame: object) -> None:
    """A signal handler that stops the class server as Ctrl-C does (the hub runs in its own session)."""
    raise KeyboardInterrupt


def run(args: argparse.Namespace) -> int:
    """`owl class serve`: exit code 2 with one line when it cannot start, else the hub's at Ctrl-C."""
    try:
        settings = prepare(args)
    except (ClassError, StudentsError, OSError) as error:
        print(f'owl class: {error}', file=sys.stderr)
        return 2
    config = hub.write_config(settings)
    # Held while the hub runs, so no `owl check` or test run on this machine leases a student's domain.
    held, shared = worlds.hold_domains(settings.domains.values())
    for domain in shared:
        owner = next(name for name, number in settings.domains.items() if number == domain)
        print(f'owl class: ROS domain {domain} ({owner}\'s) is in use by another program on this machine: '
              'its nodes and theirs may meet', flush=True)
    for stop_signal in (signal.SIGTERM, signal.SIGHUP):  # kill, or the terminal closed: as Ctrl-C
        signal.signal(stop_signal, interrupt)
    server = subprocess.Popen([str(settings.venv / 'bin' / 'jupyterhub'), '-f', str(config)],
                              cwd=settings.state, start_new_session=True)
    print(f'owl class: the class server is at https://{socket.gethostname()}:{settings.port}/ '
          f'(certificate SHA-256 {settings.certificate.fingerprint}); Ctrl-C to stop it', flush=True)
    try:
        code = server.wait()
    except KeyboardInterrupt:
        server.send_signal(signal.SIGINT)  # the hub stops every student's server and its proxy
        try:
            server.wait(HUB_STOP_TIMEOUT)
        except (subprocess.TimeoutExpired, KeyboardInterrupt):  # a hub that hangs, or Ctrl-C again
            os.killpg(server.pid, signal.SIGKILL)  # its session: the hub, its proxy, the teacher's page
            server.wait()
        code = 0
    finally:
        # What students started that outlives their servers: front doors, ROS daemons, robots.
        accounts.stop_processes(list(settings.domains))
        for handle in held:
            handle.close()
    return code
