"""owl: Owl Kit Lab's own command (next to the course's `ros2`)."""

from __future__ import annotations

import argparse
import os
import sys
import threading
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from olive_kit.description import WINDOWS_PORT, page_catalogue, tool_page
from owl_common import ros_env
from owl_humble.graph_partition import profile_in_effect, profile_protects
from owl_web.origins import port_number

from owl_cli import classroom
from owl_cli.check import command as check
from owl_cli.classroom import image, serve
from owl_cli.network import checks as network_check
from owl_cli.network import kit as kit_check
from owl_cli.network import wsl as wsl_check
from owl_cli.pages import command as pages_command


def positive_seconds(text: str) -> float:
    """An argparse type: the text as seconds, more than 0 and at most 60 (else ArgumentTypeError)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not a number of seconds") from None
    if not 0 < value <= 60:
        raise argparse.ArgumentTypeError(f'{text} is not between 0 and 60 seconds')
    return value


def read_text(path: str) -> str:
    """A file's text, '' when it cannot be read."""
    try:
        return Path(path).read_text()
    except OSError:
        return ''


def network(args: argparse.Namespace) -> int:
    """Run `owl network`: gather the facts, print one verdict a line; exit code 0 when all are ok, else 1."""
    try:
        domain_id = ros_env.domain_id()
    except ros_env.DomainIdError as error:
        print(f'owl network: problem: {error}; fix: export ROS_DOMAIN_ID=0')
        return 1
    interfaces = network_check.interfaces()
    addresses = [*network_check.MODULE_ADDRESSES, network_check.FACTORY_ADDRESS]
    answering = dict.fromkeys(addresses, False)
    # Only on the modules' own link: through a default route a router's refusal would look like an
    # answer, and the probes would go out to a network that is not the kit's.
    if network_check.on_kit_subnet(interfaces):
        with ThreadPoolExecutor(len(addresses)) as pool:
            answering = dict(zip(addresses, pool.map(lambda a: network_check.answers(a, args.timeout),
                                                     addresses), strict=True))
    distributions = network_check.olive_nodes(domain_id, args.discovery_time)
    profile = profile_in_effect()
    facts = network_check.NetworkFacts(
        discovery_range=ros_env.discovery_range(),
        domain_id=domain_id, interfaces=interfaces, answering=answering,
        olive_nodes=sorted(distributions), distributions=distributions,
        graph_profile=str(profile) if profile else None,
        graph_protected=profile is not None and profile_protects(profile),
        wsl=wsl_check.wsl_facts(read_text('/proc/version'), os.environ, wsl_check.wslinfo_networking_mode(),
                                [(i.name, i.address) for i in interfaces]))
    if not facts.olive_nodes and domain_id != 0 and any(answering.values()):
        facts.olive_nodes_in_domain_0 = sorted(network_check.olive_nodes(0, args.discovery_time))
    verdicts = network_check.verdict(facts)
    if args.kit:
        reports = kit_check.check_kit(domain_id, args.discovery_time, distributions)
        verdicts += [network_check.Verdict(ok, text) for ok, text in kit_check.kit_verdicts(reports)]
    for line in verdicts:
        print(f'owl network: {line}')
    return 0 if all(v.ok for v in verdicts) else 1




def windows(args: argparse.Namespace) -> int:
    """Run `owl windows`: serve the windows' page until Ctrl-C; exit code 1 when it cannot start."""
    # Imported here: only this command needs the venv's start-up hook (the windows' folder).
    from owl_web.server import WebServer

    from owl_cli.windows.folder import default_windows_dir, private_root
    from owl_cli.windows.page import STATIC_DIR, WindowsPage

    folder = Path(args.folder or os.environ.get('OWL_WINDOWS_DIR') or default_windows_dir())
    try:
        private_root(str(folder))
    except OSError as error:
        print(f'owl windows: cannot use {folder}: {error.strerror or error}', file=sys.stderr)
        return 1
    try:
        server = WebServer('owl windows', STATIC_DIR, args.port)
        server.join_front_door(tool_page('windows'), page_catalogue())
    except OSError as error:
        print(f'owl windows: cannot serve on 127.0.0.1:{args.port}: {error.strerror or error} '
              '(is another owl windows running? choose a port with --port N)', file=sys.stderr)
        return 1
    except ValueError as error:
        print(f'owl windows: {error}', file=sys.stderr)
        return 1
    page = WindowsPage(server, folder)
    stopped = threading.Event()
    try:
        page.start()
        server.start()
        print(f'owl windows: open {server.address} in a browser: the windows of programs without a display '
              f'(from {folder}); Ctrl-C to quit', flush=True)
        stopped.wait()
    except KeyboardInterrupt:
        pass  # Ctrl-C is how a page server is stopped
    finally:
        page.stop()
        server.stop()
    return 0


def main(argv: list[str] | None = None) -> int:
    """The `owl` command: run the sub-command argv names (None: sys.argv); its exit code, 130 at Ctrl-C."""
    parser = argparse.ArgumentParser(prog='owl', description=__doc__)
    commands = parser.add_subparsers(dest='command', metavar='COMMAND', required=True)
    check_network = commands.add_parser(
        'network', help='check the way to the Olive modules: interfaces, addresses, ROS domain, discovery',
        description=network_check.__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    check_network.add_argument('--timeout', type=positive_seconds, default=0.5, metavar='SECONDS',
                               help='how long each module address may take to answer (default 0.5)')
    check_network.add_argument('--discovery-time', type=positive_seconds, default=3.0, metavar='SECONDS',
                               help='how long to listen for the modules\' ROS nodes (default 3)')
    check_network.add_argument('--kit', action='store_true',
                               help='then check each Olive module found end to end: its ROS 2 distribution '
                                    'and one message each way')
    check_network.set_defaults(run=network)
    show_windows = commands.add_parser(
        'windows', help='the windows of programs without a display (cv2.imshow, pygame) on a local page, '
                        'with their keys',
        description='Serve the windows that programs without a display open (cv2.imshow, a pygame '
                    'display; the venv writes their frames to a folder) as one live page on 127.0.0.1, '
                    'and send the keys pressed on it to those programs.')
    show_windows.add_argument('--port', type=port_number, default=WINDOWS_PORT,
                              help=f'HTTP port on 127.0.0.1 (default: {WINDOWS_PORT}; 0 picks a free one)')
    show_windows.add_argument('--folder', metavar='DIR',
                              help='the windows\' folder (default: $OWL_WINDOWS_DIR, else the one the '
                                   'programs use by default)')
    show_windows.set_defaults(run=windows)
    check_exercise = commands.add_parser(
        'check', help="check a course exercise in your workspace (owl check --list)",
        description=check.__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    check.add_arguments(check_exercise)
    check_exercise.set_defaults(run=check.check)
    list_pages = commands.add_parser(
        'pages', help='the front door (one address for every page) and every page, running or not',
        description=pages_command.__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    pages_command.add_arguments(list_pages)
    list_pages.set_defaults(run=pages_command.run)
    teach = commands.add_parser('class', help='a class server on JupyterHub: every student in a browser',
                                description=classroom.__doc__)
    class_commands = teach.add_subparsers(dest='class_command', metavar='COMMAND', required=True)
    serve_class = class_commands.add_parser(
        'serve', help='start the class server for the students of a class list (as root)',
        description=serve.__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    serve.add_arguments(serve_class)
    serve_class.set_defaults(run=serve.run)
    class_image = class_commands.add_parser(
        'image', help="make this checkout a class's single-user image for Kubernetes (while building it)",
        description=image.__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    image.add_arguments(class_image)
    class_image.set_defaults(run=image.run)
    args = parser.parse_args(argv)
    try:
        return args.run(args)
    except KeyboardInterrupt:
        return 130


if __name__ == '__main__':
    sys.exit(main())
