"""owl check: checks a student's exercise of the course (sections 3.4 to 4.7) over real ROS 2.

owl check --list                       the exercises and projects, with their ids
owl check ID... [--workspace DIR]      build the package if needed, run the checks, one line per criterion
owl check --all [--workspace DIR]      every exercise whose package is in the workspace, then a table

Each check starts what the exercise needs (the simulated kit, turtlesim, a service server) and
your node in a private ROS domain, drives it from outside through the course's topics, services
and parameters, and stops everything again. Exit code 0: every criterion passed; 1: one failed;
2: the check could not run (no workspace, no package, a failed build, an unknown id).
"""

from __future__ import annotations

import argparse
import json
import os
import shlex
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path

from owl_cli.check import catalogue
from owl_cli.check import workspace as ws
from owl_cli.check.catalogue import Exercise
from owl_cli.check.report import (
    CHECK_DONE,
    RESULT_PREFIX,
    WORKSPACE_VARIABLE,
    Criterion,
    ExerciseResult,
    criterion_line,
    exit_code,
    record_latest,
    results_file,
    share_latest,
    summary_table,
    to_json,
)
from owl_cli.command import Command

# s: the most one check may take from its begin to its last criterion. Each check aims at well under
# 30 s and each of its waits ends by itself: this is a backstop, wide enough for a machine eight times
# slower than usual (a loaded class server) to still get a verdict rather than a stop.
HARD_LIMIT = 150.0
CLEANUP_LIMIT = 30.0  # s for a check's clean-up after its last criterion (it stops its nodes)
BUILD_LIMIT = 900.0


def build(workspace: Path, names: list[str], quiet: bool) -> str | None:
    """Colcon build of the packages; None when it worked, else the build's last error line."""
    command = ws.build_command(names)
    if not quiet:
        print(f'owl check: building {", ".join(sorted(names))} ({shlex.join(command)})', flush=True)
    try:
        done = subprocess.run(
            command, cwd=workspace, capture_output=True, text=True, timeout=BUILD_LIMIT, check=False
        )
    except FileNotFoundError:
        return "colcon is not on PATH: run 'source env.sh' in the Owl Kit Lab folder first"
    except subprocess.TimeoutExpired:
        return f'colcon build took longer than {BUILD_LIMIT:.0f} s'
    if done.returncode != 0:
        return ws.last_error_line(done.stdout + '\n' + done.stderr)
    return None


class CheckRun:
    """One exercise's check in a process of its own (owl_cli.check.ros), started before its turn.

    The process imports, leases its ROS domain and starts its probe node while the check before it
    runs; begin() starts the check. Once every criterion is out (CHECK_DONE) owl check goes on to
    the next exercise while this one stops its nodes; finish() waits for that and reports a crash.
    """

    def __init__(self, exercise_id: str, command: list[str], env: dict[str, str]) -> None:
        self.result = ExerciseResult(exercise_id)
        self.other: list[str] = []
        self.on_criterion: Callable[[Criterion], None] = lambda c: None
        self.started = time.monotonic()
        self.done = threading.Event()  # CHECK_DONE, or the process's output ended
        self.all_out = False  # CHECK_DONE came: what is left is the clean-up
        self.finished = False
        self.process = subprocess.Popen(
            command,
            env=env,
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.STDOUT,
            text=True,
            errors='replace',
            start_new_session=True,
        )
        self.reader = threading.Thread(target=self._read, daemon=True)
        self.reader.start()

    def _read(self) -> None:
        assert self.process.stdout is not None
        for line in self.process.stdout:
            if line.startswith(RESULT_PREFIX):
                self._add(Criterion.from_dict(json.loads(line[len(RESULT_PREFIX) :])))
            elif line.rstrip('\n') == CHECK_DONE:
                self.all_out = True
                self.done.set()
            else:
                self.other.append(line.rstrip())
        self.done.set()

    def _add(self, criterion: Criterion) -> None:
        self.result.criteria.append(criterion)
        self.on_criterion(criterion)

    def begin(self, on_criterion: Callable[[Criterion], None]) -> None:
        """Start the check (its set-up may still be under way); on_criterion gets each criterion."""
        self.on_criterion = on_criterion
        self.started = time.monotonic()
        assert self.process.stdin is not None
        try:
            self.process.stdin.write('begin\n')
            self.process.stdin.close()
        except OSError:
            pass  # it ended during its set-up: finish() says why

    def remaining(self) -> float:
        """Seconds left of the hard time limit, from begin()."""
        return max(0.0, self.started + HARD_LIMIT - time.monotonic())

    def wait_done(self) -> None:
        """Wait until every criterion is out (or the process ended), else stop it at the hard time limit."""
        # The process's end counts too: a process it left behind may hold its output open.
        while not self.done.wait(min(0.5, self.remaining())) and self.process.poll() is None:
            if self.remaining() == 0:
                # SIGTERM lets the check stop what it started; SIGKILL if even that hangs.
                self.kill(15.0)
                self._add(Criterion(
                    f'the check ends within {HARD_LIMIT:.0f} s',
                    False,
                    'the check was stopped: a node that never answers or never ends',
                ))
                break
        self.result.seconds = time.monotonic() - self.started

    def kill(self, grace: float) -> None:
        """SIGTERM to the check's process group, SIGKILL after grace s."""
        try:
            os.killpg(self.process.pid, 15)
            self.process.wait(grace)
        except subprocess.TimeoutExpired:
            os.killpg(self.process.pid, 9)
        except ProcessLookupError:
            pass  # it has just ended by itself
        self.process.wait()

    def finish(self) -> ExerciseResult:
        """Wait for the check's clean-up to end; a crash or a check that could not run is in the result."""
        if self.finished:
            return self.result
        self.finished = True
        try:
            self.process.wait(CLEANUP_LIMIT)
        except subprocess.TimeoutExpired:
            self.kill(15.0)
        self.reader.join(5)
        code = self.process.returncode
        if code not in (0, -15, None) and not self.result.criteria:
            self.result.error = f'the check itself failed: {" | ".join(self.other[-5:]) or "no output"}'
        elif code != 0 and any('Traceback' in line for line in self.other):
            self._add(Criterion('the check ran to its end', False, ' | '.join(self.other[-3:])))
        return self.result


def start_check(exercise: Exercise, workspace: Path) -> CheckRun:
    """The exercise's CheckRun, in a shell that sourced the workspace (it waits for begin())."""
    setup = workspace / 'install' / 'local_setup.bash'
    python = shlex.quote(sys.executable)
    script = f'source {shlex.quote(str(setup))} && exec {python} -m owl_cli.check.ros --wait {exercise.id}'
    return CheckRun(exercise.id, ['bash', '-c', script], {**os.environ, WORKSPACE_VARIABLE: str(workspace)})


def run_checks(
    exercises: list[Exercise],
    workspace: Path,
    on_criterion: Callable[[Criterion], None],
    on_start: Callable[[Exercise], None],
    on_result: Callable[[ExerciseResult], None],
) -> list[ExerciseResult]:
    """Check the exercises in turn, each one's set-up and clean-up beside the checks next to it.

    The next exercise's process sets up while this one runs, the clean-up of the one before runs
    while this one starts: only the checks themselves, from begin() to CHECK_DONE, run one at a
    time. on_result gets each result once its criteria are in.
    """
    runs: list[CheckRun] = []
    upcoming = start_check(exercises[0], workspace)
    for index, exercise in enumerate(exercises):
        run = upcoming
        on_start(exercise)
        run.begin(on_criterion)
        if runs:
            runs[-1].finish()
        runs.append(run)
        if index + 1 < len(exercises):
            upcoming = start_check(exercises[index + 1], workspace)
        run.wait_done()
        if not run.all_out or index + 1 == len(exercises):
            run.finish()  # a check that crashed or was stopped: its result is complete before it is shown
        on_result(run.result)
    runs[-1].finish()
    return [run.result for run in runs]


def attempted(exercise: Exercise, workspace: Path, available: dict[str, ws.Package]) -> bool:
    """For --all: whether the workspace holds something of this exercise to check.

    Of the course's "choose one" exercises (3.6: currency or factorial) only those whose
    executable is installed; params_file only when the workspace (or ~/Documents) has a file.
    """
    if not exercise.package:
        return bool(ws.parameter_files(workspace, Path.home()))
    if exercise.choice:
        subject, role = exercise.id.split('_')
        return any(
            ws.find_executable(ws.executables(workspace, name), subject, role) for name in available
        )
    return True


def check(args: argparse.Namespace) -> int:
    """Run `owl check` for the parsed arguments and return its exit code (0, 1 or 2, see above).

    Builds the packages the exercises need when they are stale, then checks each exercise in turn,
    printing one line per criterion (or, with --json, one JSON document at the end).
    """
    if args.list:
        print('\n'.join(catalogue.listing()))
        return 0
    if args.all == bool(args.exercises):
        print('owl check: give exercise ids or --all (owl check --list lists the ids)', file=sys.stderr)
        return 2
    for exercise_id in args.exercises:
        exercise = catalogue.find(exercise_id)
        if exercise is None:
            print(catalogue.unknown_id_message(exercise_id), file=sys.stderr)
            return 2
        if not exercise.checkable:
            print(catalogue.not_checked_message(exercise), file=sys.stderr)
            return 2
    try:
        workspace = ws.find_workspace(args.workspace or Path.cwd())
        available = ws.packages(workspace)
    except ws.WorkspaceError as error:
        print(f'owl check: {error}', file=sys.stderr)
        return 2
    if args.exercises:
        exercises = [catalogue.BY_ID[i] for i in dict.fromkeys(args.exercises)]
        for missing in sorted({e.package for e in exercises if e.package} - set(available)):
            print(
                f"owl check: no package '{missing}' in {workspace / 'src'} (the course creates it with "
                f"'ros2 pkg create {missing} --build-type ament_python')",
                file=sys.stderr,
            )
            return 2
    else:
        exercises = [e for e in catalogue.CHECKABLE if e.package in available or not e.package]
        if not exercises:
            print(f"owl check: none of the course's packages is in {workspace / 'src'}", file=sys.stderr)
            return 2
    wanted = sorted({name for e in exercises for name in ws.needed(e.package, available)})
    to_build = ws.stale(workspace, wanted, available)
    if to_build:
        problem = build(workspace, to_build, args.json)
        if problem:
            print(f'owl check: colcon build failed: {problem}', file=sys.stderr)
            return 2
    if args.all:
        exercises = [e for e in exercises if attempted(e, workspace, available)]

    def started(exercise: Exercise) -> None:
        if not args.json:
            print(f'owl check {exercise.id} (section {exercise.section}): {exercise.description}', flush=True)

    def ended(result: ExerciseResult) -> None:
        if not args.json:
            if result.error:
                print(f'  {result.error}')
            verdict = (
                'passed' if result.passed else f'FAILED ({result.failed_count} of {len(result.criteria)})'
            )
            print(f'{result.exercise}: {verdict} in {result.seconds:.1f} s', flush=True)

    results = run_checks(
        exercises,
        workspace,
        (lambda c: None) if args.json else (lambda c: print(criterion_line(c), flush=True)),
        started,
        ended,
    )
    record = results_file(os.environ)
    try:
        record_latest(record, results, {e.id: e.section for e in exercises}, str(workspace))
    except OSError as error:
        print(f'owl check: the results could not be kept in {record}: {error.strerror or error}',
              file=sys.stderr)
    problem = share_latest(record, os.environ)  # on a class server: to the teacher's page
    if problem:
        print(f'owl check: {problem}', file=sys.stderr)
    if args.json:
        print(to_json(results, str(workspace)))
    elif len(results) > 1:
        print()
        print('\n'.join(summary_table(results)))
    return exit_code(results)


class CheckCommand(Command):
    """`owl check ID... | --all | --list`."""

    help = 'check a course exercise in your workspace (owl check --list)'
    description = sys.modules[__name__].__doc__  # the module's (in here __doc__ is the class's)
    formatter_class = argparse.RawDescriptionHelpFormatter

    def add_arguments(self, parser: argparse.ArgumentParser, cli_name: str) -> None:
        """The exercise ids, --workspace, --list, --all, --json."""
        parser.add_argument('exercises', nargs='*', metavar='ID', help='exercise ids (see --list)')
        parser.add_argument(
            '--workspace',
            type=Path,
            metavar='DIR',
            help='the colcon workspace (default: the current folder or the one above it)',
        )
        parser.add_argument('--list', action='store_true', help='list the exercises and projects and exit')
        parser.add_argument(
            '--all', action='store_true', help='check every exercise whose package is in the workspace'
        )
        parser.add_argument('--json', action='store_true', help='print the results as JSON (for teachers)')

    def main(self, *, parser: argparse.ArgumentParser, args: argparse.Namespace) -> int:
        """Run `owl check`."""
        return check(args)
