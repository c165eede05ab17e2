"""Section 3.7: parameters (a parameter file, upper_limit and lower_limit)."""

from __future__ import annotations

import time
from pathlib import Path

from owl_cli.check import criteria as judge
from owl_cli.check import workspace as ws
from owl_cli.check.catalogue import TERMINAL, Section
from owl_cli.check.report import Criterion
from owl_cli.check.session import (
    START_TIMEOUT,
    Session,
    values_since,
    workspace,
)

SECTION = Section()


SECTION.by_hand(
    'turtle_background',
    '3.7.1 exercise',
    'turtlesim',
    "turtlesim's background yellow, then black, with ros2 param set",
    TERMINAL,
)


# The nodes a parameter file of the course sets, with the defaults an edited file must change.
PARAMETER_FILE_NODES = {
    'turtlesim': (
        ('turtlesim', 'turtlesim_node'),
        {'background_r': 69, 'background_g': 86, 'background_b': 255},
    ),
    'random_number_publisher': (
        ('random_number_ps', 'random_number_publisher'),
        {'upper_limit': 100},
    ),
}


@SECTION.check(
    'params_file',
    '3.7.1',
    '',
    'a parameter file (ros2 param dump, edited) that --ros-args --params-file loads at start-up',
)
def check_params_file(s: Session) -> None:
    """Find the student's parameter file, check it changes a default, and start its node with it.

    The file is looked for in the workspace and ~/Documents (turtlesim.yaml first); the node it
    sets (turtlesim or random_number_publisher) must start with the file's values.
    """
    files = ws.parameter_files(workspace(), Path.home())
    files.sort(key=lambda f: f.name != 'turtlesim.yaml')
    if not s.add(
        Criterion(
            'a parameter file is found (in the workspace or ~/Documents)',
            bool(files),
            'save one as section 3.7.1 does: cd ~/Documents; ros2 param dump /turtlesim > turtlesim.yaml',
            ', '.join(str(f) for f in files[:3]),
        )
    ):
        return
    chosen, nodes, problem = files[0], {}, ''
    for candidate in files:
        try:
            nodes = ws.read_parameter_file(candidate.read_text(errors='replace'))
        except ValueError as error:
            problem = problem or f'{candidate.name}: {error}'
            continue
        if any(key.strip('/') in PARAMETER_FILE_NODES for key in nodes):
            chosen = candidate
            break
    target = next((key for key in nodes if key.strip('/') in PARAMETER_FILE_NODES), None)
    if not s.add(
        Criterion(
            f"{chosen.name} sets a node's ros__parameters (turtlesim or random_number_publisher)",
            target is not None,
            problem
            or 'the file must start with the node name, then ros__parameters:, as ros2 param dump '
            '/turtlesim writes it',
            ', '.join(nodes) or str(chosen),
        )
    ):
        return
    assert target is not None
    node = target.strip('/')
    (package, executable), defaults = PARAMETER_FILE_NODES[node]
    values = {
        name: value
        for name, value in nodes[target].items()
        if not name.startswith(('qos_overrides.', 'use_sim_time', 'start_type_description_service'))
    }
    changed = {name: value for name, value in values.items() if name in defaults and value != defaults[name]}
    s.add(
        Criterion(
            'the file changes a value from its default, as the course asks (e.g. background 0/0/0)',
            bool(changed),
            f"a fresh dump holds the defaults ({', '.join(f'{k} {v}' for k, v in defaults.items())}): "
            'edit the values in the file to see the difference',
            ', '.join(f'{k} {v}' for k, v in values.items()),
        )
    )
    env: dict[str, str | None] = {'DISPLAY': None, 'WAYLAND_DISPLAY': None}
    process = s.sandbox.command(
        ['ros2', 'run', package, executable, '--ros-args', '--params-file', str(chosen)],
        label=executable,
        env=env,
    )
    s.wait(lambda: node in s.node.get_node_names() or not process.running(), START_TIMEOUT)
    actual = s.get_parameters(node, list(values)) if process.running() else {}
    different = {name: actual.get(name) for name, value in values.items() if actual.get(name) != value}
    s.add(
        Criterion(
            f'ros2 run {package} {executable} --ros-args --params-file {chosen.name} starts it with '
            "the file's values",
            process.running() and not different,
            (
                f'the node has {", ".join(f"{k} {v!r}" for k, v in different.items())}: '
                f"the file's first key must be the node's name (/{node}) and its values of the "
                "parameters' types"
            )
            if process.running()
            else f'it did not start with the file: {judge.tail_lines(process.output, 2)}',
            ', '.join(f'{k} {actual.get(k)!r}' for k in values),
        )
    )
    process.stop(3.0)


@SECTION.check(
    'upper_limit',
    '3.7.2',
    'random_number_ps',
    "random_number_publisher's upper_limit parameter: default 100, changed with ros2 param set",
)
def check_upper_limit(s: Session) -> None:
    """Run random_number_publisher: upper_limit is 100 at start, and set to 3 it bounds the numbers."""
    from std_msgs.msg import Int32

    numbers = s.collect(Int32, '/random_numbers')
    s.student('random_number_ps', 'random_number_publisher')
    node = 'random_number_publisher'
    s.wait(lambda: node in s.node.get_node_names() and len(numbers) >= 1, START_TIMEOUT)
    default = s.get_parameter(node, 'upper_limit')
    s.add(
        Criterion(
            "declares the parameter upper_limit with the default 100 (declare_parameter('upper_limit', 100))",
            default == 100 and not isinstance(default, bool),
            'no parameter upper_limit on /random_number_publisher'
            if default is None
            else 'upper_limit must be the integer 100 at start',
            f'upper_limit = {default!r}',
        )
    )
    ok, reason = s.set_parameter(node, 'upper_limit', 3)
    s.add(Criterion('ros2 param set /random_number_publisher upper_limit 3 succeeds', ok, reason))
    since = time.monotonic() + 0.2
    s.wait(lambda: judge.range_decided(values_since(numbers, since, lambda m: m.data), 1, 3, 4), 8.0)
    values = values_since(numbers, since, lambda m: m.data)
    s.add(
        judge.in_range(
            'the numbers after upper_limit is set to 3',
            values,
            1,
            3,
            'the numbers ignore upper_limit: read it in the timer callback with '
            "self.get_parameter('upper_limit') and use it in random.randint(1, upper_limit)",
        )
    )
    s.stop_student()


@SECTION.check(
    'lower_limit',
    '3.7.2 exercise',
    'random_number_ps',
    'a parameter for the lower bound of random_number_publisher',
)
def check_lower_limit(s: Session) -> None:
    """Run random_number_publisher: a lower-bound parameter set to 10 (upper_limit 12) bounds the numbers."""
    from std_msgs.msg import Int32

    numbers = s.collect(Int32, '/random_numbers')
    s.student('random_number_ps', 'random_number_publisher')
    node = 'random_number_publisher'
    s.wait(lambda: node in s.node.get_node_names(), START_TIMEOUT)
    names = [n for n in s.parameters(node) if 'lower' in n or 'min' in n]
    if not s.add(
        Criterion(
            'declares a parameter for the lower bound (e.g. lower_limit)',
            bool(names),
            "declare_parameter('lower_limit', 1) beside upper_limit",
            ', '.join(names),
        )
    ):
        s.stop_student()
        return
    ok_upper, reason_upper = s.set_parameter(node, 'upper_limit', 12)
    ok_lower, reason_lower = s.set_parameter(node, names[0], 10)
    s.add(
        Criterion(
            f'ros2 param set of upper_limit 12 and {names[0]} 10 succeed',
            ok_upper and ok_lower,
            reason_upper or reason_lower,
        )
    )
    since = time.monotonic() + 0.2
    s.wait(lambda: judge.range_decided(values_since(numbers, since, lambda m: m.data), 10, 12, 4), 8.0)
    s.add(
        judge.in_range(
            f'the numbers after {names[0]} 10 and upper_limit 12',
            values_since(numbers, since, lambda m: m.data),
            10,
            12,
            f'read {names[0]} in the timer callback and use it in random.randint({names[0]}, upper_limit)',
        )
    )
    s.stop_student()
