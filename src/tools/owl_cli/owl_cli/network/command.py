"""The `owl network` command: its options, and the facts gathered for checks.verdict()."""

from __future__ import annotations

import argparse
import os
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from owl_common import ros_env
from owl_humble.graph_partition import profile_in_effect, profile_protects

from owl_cli.command import Command
from owl_cli.network import checks, kit, wsl


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
    interfaces = checks.interfaces()
    addresses = [*checks.MODULE_ADDRESSES, checks.FACTORY_ADDRESS]
    answering = dict.fromkeys(addresses, False)
    # Only on the modules' own link: through a default route a router's refusal would look like an
    # answer, and the probes would go out to a network that is not the kit's.
    if checks.on_kit_subnet(interfaces):
        with ThreadPoolExecutor(len(addresses)) as pool:
            answering = dict(zip(addresses, pool.map(lambda a: checks.answers(a, args.timeout),
                                                     addresses), strict=True))
    distributions = checks.olive_nodes(domain_id, args.discovery_time)
    profile = profile_in_effect()
    facts = checks.NetworkFacts(
        discovery_range=ros_env.discovery_range(),
        domain_id=domain_id, interfaces=interfaces, answering=answering,
        olive_nodes=sorted(distributions), distributions=distributions,
        graph_profile=str(profile) if profile else None,
        graph_protected=profile is not None and profile_protects(profile),
        wsl=wsl.wsl_facts(read_text('/proc/version'), os.environ, wsl.wslinfo_networking_mode(),
                          [(i.name, i.address) for i in interfaces]))
    if not facts.olive_nodes and domain_id != 0 and any(answering.values()):
        facts.olive_nodes_in_domain_0 = sorted(checks.olive_nodes(0, args.discovery_time))
    verdicts = checks.verdict(facts)
    if args.kit:
        reports = kit.check_kit(domain_id, args.discovery_time, distributions)
        verdicts += [checks.Verdict(ok, text) for ok, text in kit.kit_verdicts(reports)]
    for line in verdicts:
        print(f'owl network: {line}')
    return 0 if all(v.ok for v in verdicts) else 1


class NetworkCommand(Command):
    """`owl network [--kit]`."""

    help = 'check the way to the Olive modules: interfaces, addresses, ROS domain, discovery'
    description = checks.__doc__
    formatter_class = argparse.RawDescriptionHelpFormatter

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """--timeout, --discovery-time, --kit."""
        parser.add_argument('--timeout', type=positive_seconds, default=0.5, metavar='SECONDS',
                            help='how long each module address may take to answer (default 0.5)')
        parser.add_argument('--discovery-time', type=positive_seconds, default=3.0, metavar='SECONDS',
                            help='how long to listen for the modules\' ROS nodes (default 3)')
        parser.add_argument('--kit', action='store_true',
                            help='then check each Olive module found end to end: its ROS 2 distribution '
                                 'and one message each way')

    def main(self, *, parser: argparse.ArgumentParser, args: argparse.Namespace) -> int:
        """Run `owl network`."""
        return network(args)
