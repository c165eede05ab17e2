"""Test hosts in network namespaces (olive_sim.network_hosts): a classroom's LAN, the kit's bridge.

Creating namespaces needs root: without it the tests that use a TestLan skip with one line.
"""

from __future__ import annotations

import os
from pathlib import Path

from gates import prerequisite_missing
from olive_sim.network_hosts import Lan, NetworkSetupError, setup_problem
from owl_common.processes import RosProcess

ROOT = Path(__file__).resolve().parents[1]


class TestLan(Lan):
    """A Lan whose hosts run commands in `env.sh` shells of this checkout; close() stops them too."""

    __test__ = False  # not a test class, whatever its name says to pytest

    def __init__(self, prefix: str = 'owltest') -> None:
        problem = setup_problem()
        if problem:
            prerequisite_missing(f'{problem}, so this network test is skipped')
        try:
            super().__init__(prefix=prefix)
        except NetworkSetupError as error:
            prerequisite_missing(
                f'cannot make a network namespace here ({error}), so this network test is skipped')
        self.processes: list[RosProcess] = []

    def run(self, host: str, command: str, env: dict[str, str], label: str | None = None) -> RosProcess:
        """A shell command run on a host after `source env.sh`, as in a user's shell.

        env sets OWL_NETWORK, ROS_DOMAIN_ID... as a user's shell would (the test's own discovery range is
        not passed on).
        """
        process_env = {k: v for k, v in os.environ.items() if not k.startswith('ROS_AUTOMATIC_DISCOVERY')}
        process_env.update(env, PYTHONUNBUFFERED='1', RCUTILS_LOGGING_BUFFERED_STREAM='1')
        argv = self.exec_argv(host, ['bash', '-c', f'source {ROOT}/env.sh && exec {command}'])
        process = RosProcess(argv, process_env, label=label or f'{host}: {command}')
        self.processes.append(process)
        return process

    def close(self) -> None:
        for process in reversed(self.processes):
            if process.running():
                process.stop(timeout=3.0)
        super().close()
