"""Section 3.9: launch files (two turtles)."""

from __future__ import annotations

from owl_cli.check.catalogue import Section
from owl_cli.check.report import Criterion
from owl_cli.check.session import (
    Session,
    launch_files,
)

SECTION = Section()


@SECTION.check(
    'turtle_launch',
    '3.9',
    'olive_launch',
    "olive_launch's launch file starts two turtlesim nodes, turtle1 and turtle2",
)
def check_turtle_launch(s: Session) -> None:
    """Launch olive_launch's launch file: it starts turtle1 and turtle2 and stops cleanly at Ctrl-C."""
    files = launch_files('olive_launch')
    names = [f.name for f in files]
    chosen = next(
        (n for n in ('turtle_launch.py', 'turtle.launch.py') if n in names), names[0] if names else None
    )
    if not s.add(
        Criterion(
            'olive_launch installs a launch file (share/olive_launch/launch)',
            chosen is not None,
            "add (os.path.join('share', package_name, 'launch'), glob(...)) to data_files in setup.py",
            ', '.join(names),
        )
    ) or chosen is None:  # (add() is False when chosen is None; the test tells mypy so)
        return
    s.student_launch('olive_launch', chosen)
    s.wait(lambda: {'turtle1', 'turtle2'} <= set(s.node.get_node_names()), 20.0)
    running = sorted(set(s.node.get_node_names()) & {'turtle1', 'turtle2'})
    s.add(
        Criterion(
            f'ros2 launch olive_launch {chosen} starts two turtlesim nodes named turtle1 and turtle2',
            running == ['turtle1', 'turtle2'],
            "two Node(package='turtlesim', executable='turtlesim_node', name=...) actions",
            f'{running}',
        )
    )
    s.stop_student('Ctrl-C stops the launch cleanly (exit code 0, no traceback)', launch=True)
