"""make demo: the course's first nodes talking over real ROS 2, live for about ten seconds.

Starts the random number publisher and subscriber (section 3.5) and the temperature server
(section 3.6), calls the temperature client a few times while they run, then stops everything
with Ctrl-C's signal, as a user at a terminal would.
"""

from __future__ import annotations

import argparse
import sys
import time

from owl_common.processes import RosSandbox

CLIENT_TEMPERATURES = ('0.0', '36.6', '100')


def run_demo(seconds: float) -> int:
    with RosSandbox(echo=True) as sandbox:
        print(f'== Owl Kit Lab demo: ROS 2 domain {sandbox.domain_id}, {seconds:.0f} s. Watch it from '
              f'another shell with: source env.sh && ROS_DOMAIN_ID={sandbox.domain_id} '
              'ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST <command>', flush=True)
        nodes = [
            sandbox.run('random_number_ps', 'random_number_publisher'),
            sandbox.run('random_number_ps', 'random_number_subscriber'),
            sandbox.run('olive_srvcli', 'temp_server'),
        ]
        start = time.monotonic()
        clients = []
        for index, celsius in enumerate(CLIENT_TEMPERATURES):
            # Spread the client calls over the run so they interleave with the numbers.
            pause = start + (index + 1) * seconds / (len(CLIENT_TEMPERATURES) + 1) - time.monotonic()
            time.sleep(max(0.0, pause))
            client = sandbox.run('olive_srvcli', 'temp_client', celsius)
            client.wait(timeout=seconds)
            clients.append(client)
        time.sleep(max(0.0, start + seconds - time.monotonic()))
        print('== stopping (SIGINT, as Ctrl-C would)', flush=True)
        codes = {node.label: node.stop() for node in nodes}
    failed = {label: code for label, code in codes.items() if code != 0}
    failed.update({c.label: c.popen.returncode for c in clients if c.popen.returncode != 0})
    if failed:
        print(f'== demo finished with errors: {failed}', file=sys.stderr)
        return 1
    print('== demo finished: every node stopped cleanly', flush=True)
    return 0


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument('--seconds', type=float, default=10.0, help='how long to run (default 10)')
    args = parser.parse_args()
    try:
        return run_demo(args.seconds)
    except KeyboardInterrupt:
        print('== interrupted; every node was stopped', file=sys.stderr)
        return 130


if __name__ == '__main__':
    sys.exit(main())
