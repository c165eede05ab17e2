"""kit_hosts: the simulated Owl Kit with every module a network host of its own, as the real kit is.

    sudo -E env "PATH=$PATH" ros2 run olive_sim kit_hosts [--student-address 10.42.0.1]

Each module runs in a network namespace at the course's address (IMU 10.42.0.20, pan servo
10.42.0.8, tilt servo 10.42.0.9, camera 10.42.0.10), all on one bridge: the network bridge of
section 4.4.1. This machine joins the bridge at the student's address, so shells in open network
mode (`export OWL_NETWORK=open; source env.sh`) reach the modules over real DDS, as they would
reach the real ones. Ctrl-C stops the modules and removes the namespaces and the bridge.
"""

from __future__ import annotations

import argparse
import signal
import sys
import threading

from olive_kit.description import KIT_SUBNET, OWL_KIT, STUDENT_ADDRESS
from owl_common.processes import RosProcess, installed_executable, isolated_env

from olive_sim.network_hosts import Lan, NetworkSetupError, address_problem, setup_problem


def module_argv(lan: Lan, host: str, executable: str, parameters: dict) -> list[str]:
    """The command that runs a module's executable with its parameters in the host's network namespace."""
    args = [arg for key, value in parameters.items() for arg in ('-p', f'{key}:={value}')]
    command = [sys.executable, str(installed_executable('olive_sim', executable))]
    return lan.exec_argv(host, [*command, *(['--ros-args', *args] if args else [])])


def run(student_address: str, domain_id: int) -> int:
    """Run the kit until Ctrl-C or SIGTERM (exit code 0) or until a module stops (1), then take it down."""
    lan = Lan(prefix='owlkit', subnet=KIT_SUBNET)
    processes: list[RosProcess] = []
    try:
        env = isolated_env(domain_id, discovery_range='SUBNET')
        link = lan.join_this_machine(student_address)
        for module in OWL_KIT:
            host = f'{module.module_type}-{module.namespace}'[:20]
            lan.add_host(host, module.address)
            processes.append(RosProcess(module_argv(lan, host, module.executable, module.parameters), env,
                                        label=host, echo=True))
        print(f'kit_hosts: the kit on the bridge {KIT_SUBNET}, ROS domain {domain_id}; this machine is '
              f'{student_address} on {link}', flush=True)
        for module, namespace in zip(OWL_KIT, lan.hosts.values(), strict=True):
            print(f'  {module.module_type:6} {module.namespace:15} {module.address:11} '
                  f'(a shell on it: sudo ip netns exec {namespace} bash)', flush=True)
        print('kit_hosts: in your shells: export OWL_NETWORK=open ROS_DOMAIN_ID='
              f'{domain_id}; source env.sh   (Ctrl-C here stops the kit)', flush=True)
        stopped = threading.Event()
        signal.signal(signal.SIGINT, lambda *_: stopped.set())
        signal.signal(signal.SIGTERM, lambda *_: stopped.set())
        while not stopped.wait(0.5):
            if not all(p.running() for p in processes):
                print('kit_hosts: a module stopped; stopping the kit', file=sys.stderr)
                return 1
        return 0
    finally:
        for process in processes:
            process.stop(timeout=3.0)
        lan.close()


def main(argv: list[str] | None = None) -> int:
    """The kit_hosts command; exit code 2 for a bad argument or no way to make namespaces, 1 on failure."""
    parser = argparse.ArgumentParser(prog='kit_hosts', description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--student-address', default=STUDENT_ADDRESS,
                        help=f"this machine's address on the kit's bridge (default {STUDENT_ADDRESS})")
    parser.add_argument('--domain-id', type=int, default=0, choices=range(0, 102), metavar='0..101',
                        help='ROS_DOMAIN_ID of the modules (default 0, as real modules)')
    args = parser.parse_args(argv)
    problem = address_problem(args.student_address, KIT_SUBNET, [m.address for m in OWL_KIT])
    if problem:
        parser.exit(2, f'kit_hosts: error: --student-address: {problem}\n')
    problem = setup_problem()
    if problem:
        parser.exit(2, f'kit_hosts: error: {problem}\n')
    try:
        return run(args.student_address, args.domain_id)
    except NetworkSetupError as error:
        print(f'kit_hosts: error: {error}', file=sys.stderr)
        return 1


if __name__ == '__main__':
    sys.exit(main())
