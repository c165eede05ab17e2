"""The exercises and projects of course sections 3.4 to 4.7, the "+" extras included.

Each has an id (the course's executable name where there is one, else a short name), its section,
the package it lives in, a one-line description and its check. Exercises done by hand at a terminal
or on the hardware (3.6.1's service calls, 3.7.1's colour changes, 3.8's action goals, 4.3's debug
GUI, 4.4's PID tuning) leave nothing behind to check: they are listed with the reason
(`not_checked`).

The exercises come from plug-ins, one module per course section (owl_cli/check/exercises/), each
declaring its exercises beside their checks; setup.py lists them in the `owl_cli.exercises`
entry-point group, named by section, so another package can add a section's checks the same way.
"""

from __future__ import annotations

import difflib
from collections.abc import Callable
from dataclasses import dataclass, field
from importlib.metadata import entry_points
from typing import TYPE_CHECKING, TypeVar

if TYPE_CHECKING:
    from owl_cli.check.session import Session

    Check = Callable[[Session], None]

PLUGIN_GROUP = 'owl_cli.exercises'
# A check function as written (it may take more arguments with defaults, as check_control_servo).
CheckFunction = TypeVar('CheckFunction', bound=Callable[..., None])
TERMINAL = 'typed at a terminal (ros2 and rqt commands), it leaves nothing in a workspace to check'


@dataclass(frozen=True)
class Exercise:
    """One exercise or project of the course: its id, where it lives, and its check (None: by hand)."""

    id: str
    section: str
    package: str
    description: str
    extra: bool = False  # one of the course's "+" extras
    not_checked: str = ''  # why there is nothing to check (an exercise done by hand at a terminal)
    # The course's "choose one of the following exercises": --all checks only those of the group
    # whose executable the workspace has.
    choice: str = ''
    check: Check | None = field(default=None, compare=False, repr=False)

    @property
    def checkable(self) -> bool:
        """Whether owl check can check it: False for an exercise done by hand (see not_checked)."""
        return self.check is not None


class Section:
    """The exercises of one course section, in the course's order: what a plug-in module offers."""

    def __init__(self) -> None:
        self.exercises: list[Exercise] = []

    def check(self, exercise_id: str, section: str, package: str, description: str, *,
              extra: bool = False, choice: str = '') -> Callable[[CheckFunction], CheckFunction]:
        """Declare the function below as the check of this exercise."""
        def declare(check: CheckFunction) -> CheckFunction:
            self.exercises.append(Exercise(exercise_id, section, package, description, extra,
                                           choice=choice, check=check))
            return check
        return declare

    def by_hand(self, exercise_id: str, section: str, package: str, description: str, why: str) -> None:
        """Declare an exercise that leaves nothing to check, and why."""
        self.exercises.append(Exercise(exercise_id, section, package, description, not_checked=why))


def section_order(name: str) -> tuple[int, ...]:
    """'4.4.1' -> (4, 4, 1): plug-ins are named by the course section they check."""
    return tuple(int(part) for part in name.split('.'))


def load_exercises(group: str = PLUGIN_GROUP) -> tuple[Exercise, ...]:
    """Every plug-in's exercises, in section order; ValueError when two declare the same id."""
    plugins = sorted(entry_points(group=group), key=lambda plugin: section_order(plugin.name))
    exercises = tuple(exercise for plugin in plugins for exercise in plugin.load().exercises)
    ids = [exercise.id for exercise in exercises]
    twice = sorted({i for i in ids if ids.count(i) > 1})
    if twice:
        raise ValueError(f"owl check: more than one plug-in declares {', '.join(twice)}")
    return exercises


EXERCISES = load_exercises()

BY_ID = {exercise.id: exercise for exercise in EXERCISES}


CHECKABLE = tuple(e for e in EXERCISES if e.checkable)


def find(exercise_id: str) -> Exercise | None:
    """The exercise with this id, or None for an unknown id."""
    return BY_ID.get(exercise_id)


def closest(exercise_id: str) -> str | None:
    """The known id most like an unknown one, or None when none is close."""
    matches = difflib.get_close_matches(exercise_id, BY_ID, n=1, cutoff=0.5)
    return matches[0] if matches else None


def unknown_id_message(exercise_id: str) -> str:
    """The error line of `owl check` for an unknown id, with the closest known id when there is one."""
    suggestion = closest(exercise_id)
    hint = f"; did you mean '{suggestion}'?" if suggestion else ''
    return f"owl check: unknown exercise '{exercise_id}'{hint} ('owl check --list' lists them)"


def not_checked_message(exercise: Exercise) -> str:
    """The error line of `owl check` for an exercise done by hand, with the reason it is not checked."""
    return f'owl check: {exercise.id} (section {exercise.section}) is not checked: {exercise.not_checked}'


def listing() -> list[str]:
    """The lines of `owl check --list`: id, section, description (and why, for one not checked)."""
    width = max(len(e.id) for e in EXERCISES)
    section_width = max(len(e.section) for e in EXERCISES)
    return [
        f'{e.id:<{width}}  {e.section:<{section_width}}  {e.description}'
        + ('' if e.checkable else ' [not checked: done by hand]')
        for e in EXERCISES
    ]
