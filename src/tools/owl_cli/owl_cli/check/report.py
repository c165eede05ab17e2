"""Results of `owl check`: one line per criterion, JSON for teachers, the --all summary table."""

from __future__ import annotations

import fcntl
import json
import os
import time
import urllib.error
import urllib.request
from collections.abc import Mapping
from dataclasses import asdict, dataclass, field
from pathlib import Path

# How the check's ROS process (check/ros.py) hands each decided criterion to `owl check`: one line.
RESULT_PREFIX = 'owl-check-criterion '
# ... and that every criterion is out: what follows is the check's clean-up, which owl check lets run
# beside the next exercise's check.
CHECK_DONE = 'owl-check-done'
# The student's workspace, for the check's ROS process (its executables, its parameter files).
WORKSPACE_VARIABLE = 'OWL_CHECK_WORKSPACE'


@dataclass
class Criterion:
    """One decided criterion of a check: what was checked, whether it passed, a hint, what was measured."""

    text: str  # what is checked, in the course's terms
    passed: bool
    hint: str = ''  # for a failure: what to look at
    detail: str = ''  # what was measured (both outcomes)

    @classmethod
    def from_dict(cls, values: dict[str, object]) -> Criterion:
        """The criterion from its JSON object, as check/ros.py prints it after RESULT_PREFIX."""
        return cls(
            str(values['text']),
            bool(values['passed']),
            str(values.get('hint', '')),
            str(values.get('detail', '')),
        )


@dataclass
class ExerciseResult:
    """The outcome of one exercise's check: its criteria, how long it took, or why it could not run."""

    exercise: str
    criteria: list[Criterion] = field(default_factory=list)
    seconds: float = 0.0
    error: str = ''  # a problem that stopped the check before its criteria (exit code 2)

    @property
    def passed(self) -> bool:
        """Whether the check ran and every one of its criteria (at least one) passed."""
        return not self.error and bool(self.criteria) and all(c.passed for c in self.criteria)

    @property
    def failed_count(self) -> int:
        """How many of the criteria failed."""
        return sum(not c.passed for c in self.criteria)


def criterion_line(criterion: Criterion) -> str:
    """The printed line of a criterion: passed or FAILED, its text and detail, the hint on a failure."""
    mark = 'passed' if criterion.passed else 'FAILED'
    line = f'  {mark}: {criterion.text}'
    if criterion.detail:
        line += f' ({criterion.detail})'
    if not criterion.passed and criterion.hint:
        line += f'\n          hint: {criterion.hint}'
    return line


def exercise_lines(result: ExerciseResult) -> list[str]:
    """The lines of one exercise's report: a heading, one line per criterion and the verdict."""
    if result.error:
        return [f'owl check {result.exercise}: {result.error}']
    verdict = 'passed' if result.passed else f'FAILED ({result.failed_count} of {len(result.criteria)})'
    return (
        [f'owl check {result.exercise}:']
        + [criterion_line(c) for c in result.criteria]
        + [f'{result.exercise}: {verdict} in {result.seconds:.1f} s']
    )


def summary_table(results: list[ExerciseResult]) -> list[str]:
    """The lines of the table after several exercises: one row per exercise and a total line."""
    width = max([len('exercise')] + [len(r.exercise) for r in results])
    lines = [f'{"exercise":<{width}}  result   criteria  time', f'{"-" * width}  -------  --------  -----']
    for r in results:
        if r.error:
            state, counts = 'ERROR  ', '       -'
        else:
            state = 'passed ' if r.passed else 'FAILED '
            counts = f'{len(r.criteria) - r.failed_count:>4}/{len(r.criteria):<3}'
        lines.append(f'{r.exercise:<{width}}  {state}  {counts:>8}  {r.seconds:4.1f}s')
    passed = sum(r.passed for r in results)
    lines.append(f'{passed} of {len(results)} exercises passed in {sum(r.seconds for r in results):.1f} s')
    return lines


def to_json(results: list[ExerciseResult], workspace: str) -> str:
    """The results as the JSON document of `owl check --json` (for teachers)."""
    return json.dumps(
        {
            'workspace': workspace,
            'passed': all(r.passed for r in results),
            'exercises': [
                {
                    'exercise': r.exercise,
                    'passed': r.passed,
                    'seconds': round(r.seconds, 2),
                    'error': r.error,
                    'criteria': [asdict(c) for c in r.criteria],
                }
                for r in results
            ],
        },
        indent=2,
    )


def exit_code(results: list[ExerciseResult]) -> int:
    """0 when every criterion passed, 2 when a check could not run (bad input), else 1."""
    if any(r.error for r in results):
        return 2
    return 0 if all(r.passed for r in results) else 1


def results_file(environ: Mapping[str, str]) -> Path:
    """Where owl check keeps each exercise's latest result (the class server's teacher page reads it).

    $XDG_STATE_HOME/owl-kit-lab/check-results.json, else ~/.local/state/owl-kit-lab/check-results.json.
    """
    state = environ.get('XDG_STATE_HOME') or str(Path(environ.get('HOME', '/')) / '.local' / 'state')
    return Path(state) / 'owl-kit-lab' / 'check-results.json'


def read_latest(path: Path) -> dict[str, dict[str, object]]:
    """Each exercise's latest recorded result; none when the file is missing or not such a record."""
    try:
        record = json.loads(path.read_text())
    except (OSError, ValueError):
        return {}
    exercises = record.get('exercises') if isinstance(record, dict) else None
    if not isinstance(exercises, dict):
        return {}
    return {name: value for name, value in exercises.items() if isinstance(value, dict)}


def record_latest(path: Path, results: list[ExerciseResult], sections: Mapping[str, str], workspace: str,
                  now: float | None = None) -> None:
    """Keep these results as their exercises' latest in path, beside the others' (OSError if it cannot)."""
    path.parent.mkdir(parents=True, exist_ok=True)
    with open(path.with_name(f'.{path.name}.lock'), 'w') as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # two checks at once: each keeps the other's exercises
        latest = read_latest(path)
        at = time.time() if now is None else now
        for r in results:
            latest[r.exercise] = {'passed': r.passed, 'failed': r.failed_count, 'criteria': len(r.criteria),
                                  'error': r.error, 'section': sections.get(r.exercise, ''), 'at': at,
                                  'workspace': workspace}
        written = path.with_name(f'.{path.name}.{os.getpid()}')
        written.write_text(json.dumps({'exercises': latest}, indent=1, sort_keys=True) + '\n')
        written.replace(path)  # whole or not at all: a reader never sees half a file


CLASS_RESULTS_VARIABLE = 'OWL_CLASS_RESULTS_URL'  # set by the class server (owl_cli.classroom.hub)
SHARE_TIMEOUT = 5.0  # s for the teacher's page to take the results


def share_latest(path: Path, environ: Mapping[str, str]) -> str | None:
    """Send the latest results in path to the class's teacher page, when this is a class server's terminal.

    The class server's terminals have OWL_CLASS_RESULTS_URL and the student's server token
    (JUPYTERHUB_API_TOKEN, which tells the page who sends them). None when they were taken or there
    is no class; else one line saying why the page did not take them.
    """
    url, token = environ.get(CLASS_RESULTS_VARIABLE), environ.get('JUPYTERHUB_API_TOKEN')
    if not url or not token:
        return None
    body = json.dumps({'exercises': read_latest(path)}).encode()
    try:
        request = urllib.request.Request(url, data=body, method='POST', headers={
            'Authorization': f'token {token}', 'Content-Type': 'application/json'})
        with urllib.request.urlopen(request, timeout=SHARE_TIMEOUT):
            return None
    except urllib.error.HTTPError as error:
        try:
            reason = json.loads(error.read()).get('error') or error.reason
        except (ValueError, AttributeError):
            reason = error.reason
        return f"the teacher's page did not take these results ({error.code}: {reason})"
    except (OSError, ValueError) as error:  # no answer, a malformed URL
        return f"the teacher's page did not take these results ({getattr(error, 'reason', error)})"
