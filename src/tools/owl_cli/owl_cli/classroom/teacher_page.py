"""The teacher's page: each student, when they last worked, and their latest `owl check` results.

A JupyterHub service (`/services/owl-teacher/`), started by the hub with the hub's venv and this
package's folder on PYTHONPATH (this module and what it imports need only the standard library,
plus JupyterHub's own service library and tornado, which the hub's venv has). Who may open it is
JupyterHub's to say: a service is open to the accounts whose roles give access to it, which the
admin role does and the default user role does not, so the teacher (the hub's admin) gets the page
and a student the hub's 403.

The results come to it: a student's `owl check`, run in their JupyterLab terminal, sends its latest
results to OWL_CLASS_RESULTS_URL (api/results here) with the token of the student's server
(JUPYTERHUB_API_TOKEN), the hub says whose token it is, and the page keeps them in RESULTS of the
state folder. Nothing is read from a student's home, so the page works the same where homes are
pods' volumes (Kubernetes) as on one machine.

The page shows the class roll that `owl class serve` writes (ROLL in the state folder: the
students in the class list's order, and the course's sections with their checkable exercises),
one row per student, one column per section, and refreshes its table every few seconds.
"""

from __future__ import annotations

import html
import json
import os
import sys
import time
from collections import Counter
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from owl_cli.check.report import read_latest

ROLL = 'class-roll.json'
RESULTS = 'check-results'  # in the state folder: one file per student, as the page received it
SERVICE_NAME = 'owl-teacher'
REFRESH_SECONDS = 3
MAX_RESULTS_BODY = 256 * 1024  # bytes: a whole course's results are a few KiB
RESULT_FIELDS: dict[str, type | tuple[type, ...]] = {  # what the page keeps of each result
    'passed': bool, 'failed': int, 'criteria': int, 'section': str, 'at': (int, float)}


@dataclass(frozen=True)
class Roll:
    """The class as the page shows it: the students in order, each section's exercises in the course's."""

    students: list[str]
    sections: list[tuple[str, list[str]]]

    def to_json(self) -> str:
        """The roll as `owl class serve` writes it."""
        return json.dumps({'students': self.students, 'sections': self.sections}, indent=1) + '\n'

    @classmethod
    def from_json(cls, text: str) -> Roll:
        """The roll from its JSON (ValueError when it is not one)."""
        record = json.loads(text)
        students, sections = record['students'], record['sections']
        if not all(isinstance(name, str) for name in students):
            raise ValueError('students must be names')
        return cls(list(students), [(str(section), [str(e) for e in ids]) for section, ids in sections])


def sections_of(exercises: list[tuple[str, str]]) -> list[tuple[str, list[str]]]:
    """(section, exercise ids) in first-seen order, from (exercise id, section) pairs in course order."""
    grouped: dict[str, list[str]] = {}
    for exercise, section in exercises:
        grouped.setdefault(section, []).append(exercise)
    return list(grouped.items())


def age(seconds: float) -> str:
    """A duration as a teacher reads it: 'just now', '4 min ago', '2 h ago', '3 days ago'."""
    if seconds < 60:
        return 'just now'
    if seconds < 3600:
        return f'{int(seconds // 60)} min ago'
    if seconds < 86400:
        return f'{int(seconds // 3600)} h ago'
    return f'{int(seconds // 86400)} days ago'


def table_html(roll: Roll, results: dict[str, dict[str, dict[str, Any]]], activity: dict[str, float],
               now: float) -> str:
    """The page's table: a row per student, a column per section, each exercise passed, failed or not run.

    results: each student's latest result per exercise (owl_cli.check.report.read_latest); activity:
    when each student's server last saw them (seconds since the epoch), if it did.
    """
    head = ''.join(f'<th scope="col">{html.escape(section)}</th>' for section, _ in roll.sections)
    rows = []
    for name in roll.students:
        mine = results.get(name, {})
        times = [float(r['at']) for r in mine.values() if isinstance(r.get('at'), (int, float))]
        if name in activity:
            times.append(activity[name])
        last = age(now - max(times)) if times else 'never'
        cells = []
        counts: Counter[str] = Counter()
        for _, exercises in roll.sections:
            marks = []
            for exercise in exercises:
                record = mine.get(exercise)
                state = ('not-run' if record is None
                         else 'passed' if record.get('passed') is True else 'failed')
                counts[state] += 1
                label = {'not-run': 'not run', 'passed': 'passed', 'failed': 'FAILED'}[state]
                marks.append(f'<span class="{state}" data-exercise="{html.escape(exercise)}" '
                             f'title="{html.escape(exercise)}: {label}">{html.escape(exercise)}</span>')
            cells.append(f'<td>{" ".join(marks)}</td>')
        total = sum(len(exercises) for _, exercises in roll.sections)
        # The sum first: a course has more sections than a screen is wide.
        failed = f", {counts['failed']} failed" if counts['failed'] else ''
        summary = f"{counts['passed']} of {total} passed{failed}"
        link = f'<a href="../../user/{html.escape(name)}/lab" target="_blank">{html.escape(name)}</a>'
        rows.append(f'<tr data-student="{html.escape(name)}"><th scope="row">{link}</th>'
                    f'<td class="last">{last}</td><td class="sum">{summary}</td>{"".join(cells)}</tr>')
    return (f'<table id="progress"><thead><tr><th scope="col">student</th><th scope="col">last worked</th>'
            f'<th scope="col">exercises</th>{head}</tr></thead><tbody>{"".join(rows)}</tbody></table>')


PAGE = """<!doctype html>
<html lang="en"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<meta name="xsrf-token" content="{xsrf}">
<title>Owl Kit Lab: the class</title>
<style>
body {{ font-family: system-ui, sans-serif; margin: 1rem; }}
table {{ border-collapse: collapse; }}
th, td {{ border: 1px solid #ccc; padding: .3rem .5rem; text-align: left; }}
span {{ display: inline-block; margin: .1rem; padding: 0 .3rem; border-radius: .2rem; font-size: .85rem; }}
.passed {{ background: #c8f0c8; }} .failed {{ background: #f6c6c6; }} .not-run {{ color: #888; }}
.wrap {{ overflow-x: auto; }}
/* the names stay in view while the sections scroll */
th[scope=row], thead th:first-child {{ position: sticky; left: 0; background: #fff; }}
#stale {{ background: #fff3d6; padding: .4rem .6rem; }}
</style></head><body>
<h1>The class</h1>
<p id="stale" hidden></p>
<p>Each student's latest <code>owl check</code> results by course section (green passed, red failed,
grey not run yet), refreshed every {refresh} s. A name opens that student's JupyterLab (as the hub's
admin).</p>
<div class="wrap" id="table">{table}</div>
<script>
// The hub takes its login cookie on a page's own requests only with the page's XSRF token.
const token = document.querySelector('meta[name=xsrf-token]').content;
const stale = document.getElementById('stale');
setInterval(async () => {{
  let why = '';
  try {{
    const answer = await fetch('api/table', {{ cache: 'no-store', headers: {{ 'X-XSRFToken': token }} }});
    if (answer.ok) document.getElementById('table').innerHTML = await answer.text();
    else if (answer.status === 403) why = 'signed out: reload the page to sign in again';
    else why = `the hub answered ${{answer.status}}`;
  }} catch (error) {{
    why = 'the hub does not answer';
  }}
  stale.hidden = !why;
  stale.textContent = why ? `Not refreshed (${{why}}); the table shows an earlier state.` : '';
}}, {refresh_ms});
</script></body></html>
"""


def page_html(table: str, xsrf: str) -> str:
    """The whole page around the table; xsrf is the token its refreshes send (the hub's rule)."""
    return PAGE.format(table=table, xsrf=html.escape(xsrf), refresh=REFRESH_SECONDS,
                       refresh_ms=REFRESH_SECONDS * 1000)


def parse_results(body: bytes, exercises: list[str]) -> dict[str, dict[str, Any]]:
    """The results a student's `owl check` sent ({"exercises": {id: record}}), each record's known fields.

    Exercises this class does not check are left out; ValueError (one line) for anything that is not
    such a message.
    """
    if len(body) > MAX_RESULTS_BODY:
        raise ValueError(f'results over {MAX_RESULTS_BODY // 1024} KiB')
    try:
        message = json.loads(body)
    except (ValueError, UnicodeDecodeError):
        raise ValueError('results must be JSON') from None
    sent = message.get('exercises') if isinstance(message, dict) else None
    if not isinstance(sent, dict):
        raise ValueError('results must be {"exercises": {exercise: result}}')
    kept = {}
    for exercise, record in sent.items():
        if exercise not in exercises:
            continue
        if not isinstance(record, dict) or not isinstance(record.get('passed'), bool):
            raise ValueError(f'{exercise}: a result needs "passed": true or false')
        kept[exercise] = {field: record[field] for field, kind in RESULT_FIELDS.items()
                          if isinstance(record.get(field), kind)}
    return kept


def store_results(folder: Path, name: str, results: dict[str, dict[str, Any]]) -> None:
    """Keep a student's latest results (whole or not at all: a refresh never reads half a file)."""
    folder.mkdir(mode=0o700, exist_ok=True)
    written = folder / f'.{name}.{os.getpid()}'
    written.write_text(json.dumps({'exercises': results}, indent=1, sort_keys=True) + '\n')
    written.replace(folder / f'{name}.json')


def class_results(roll: Roll, folder: Path) -> dict[str, dict[str, dict[str, Any]]]:
    """Each student's latest results as the page received them (none yet: none)."""
    return {name: read_latest(folder / f'{name}.json') for name in roll.students}


def main(argv: list[str] | None = None) -> int:
    """Serve the page for the class whose state folder is the one argument (the hub starts it)."""
    args = sys.argv[1:] if argv is None else argv
    if len(args) != 1:
        print('usage: python -m owl_cli.classroom.teacher_page STATE_FOLDER', file=sys.stderr)
        return 2
    roll_path = Path(args[0]) / ROLL
    try:
        Roll.from_json(roll_path.read_text())
    except (OSError, ValueError, KeyError, TypeError) as error:
        print(f'teacher page: cannot read the class roll {roll_path}: {error}', file=sys.stderr)
        return 2
    try:
        serve(roll_path)
    except KeyboardInterrupt:  # the teacher's Ctrl-C reaches the hub's whole process group: a clean stop
        pass
    return 0


def serve(roll_path: Path) -> None:
    """Run the service's web server until the hub stops it (in the hub's venv: tests/test_class_server.py)."""
    import asyncio
    import secrets
    from datetime import datetime
    from urllib.parse import urlsplit

    from jupyterhub.services.auth import HubOAuthCallbackHandler, HubOAuthenticated
    from jupyterhub.utils import url_path_join
    from tornado import web
    from tornado.httpclient import AsyncHTTPClient, HTTPClientError

    async def activity() -> dict[str, float]:
        """When the hub last saw each user, from its API (the service's token may list users' activity)."""
        answer = await AsyncHTTPClient().fetch(
            url_path_join(os.environ['JUPYTERHUB_API_URL'], 'users'),
            headers={'Authorization': f"token {os.environ['JUPYTERHUB_API_TOKEN']}"})
        seen = {}
        for user in json.loads(answer.body):
            if user.get('last_activity'):
                when = datetime.fromisoformat(user['last_activity'].replace('Z', '+00:00'))
                seen[user['name']] = when.timestamp()
        return seen

    store = roll_path.parent / RESULTS

    async def current_table() -> str:
        roll = Roll.from_json(roll_path.read_text())  # read at each refresh: a restart may change it
        return table_html(roll, class_results(roll, store), await activity(), time.time())

    async def owner_of(token: str) -> str | None:
        """Whose token it is, as the hub says (None: not a token of this hub's)."""
        try:
            answer = await AsyncHTTPClient().fetch(url_path_join(os.environ['JUPYTERHUB_API_URL'], 'user'),
                                                   headers={'Authorization': f'token {token}'})
        except HTTPClientError:
            return None
        name = json.loads(answer.body).get('name')
        return name if isinstance(name, str) else None

    class Page(HubOAuthenticated, web.RequestHandler):
        @web.authenticated
        async def get(self) -> None:
            self.set_header('Cache-Control', 'no-store')
            self.finish(page_html(await current_table(), self.xsrf_token.decode()))

    class Table(HubOAuthenticated, web.RequestHandler):
        async def get(self) -> None:
            self.set_header('Cache-Control', 'no-store')
            if self.current_user is None:  # a refresh is not sent to the login form: the page says so
                self.set_status(403)
                self.finish('not signed in')
                return
            self.finish(await current_table())

    class Results(web.RequestHandler):
        """POST api/results: a student's `owl check` sends its latest results with their server's token."""

        def refuse(self, status: int, reason: str) -> None:
            self.set_status(status)
            self.finish({'error': reason})

        async def post(self) -> None:
            scheme, _, token = self.request.headers.get('Authorization', '').partition(' ')
            name = await owner_of(token.strip()) if scheme.lower() == 'token' and token.strip() else None
            if name is None:
                return self.refuse(403, "send the results with your server's token "
                                        '(Authorization: token $JUPYTERHUB_API_TOKEN)')
            roll = Roll.from_json(roll_path.read_text())
            if name not in roll.students:
                return self.refuse(403, f'{name} is not a student of this class: nothing kept')
            try:
                results = parse_results(self.request.body, [e for _, ids in roll.sections for e in ids])
            except ValueError as error:
                return self.refuse(400, str(error))
            store_results(store, name, results)
            self.finish({'kept': sorted(results)})

    prefix = os.environ['JUPYTERHUB_SERVICE_PREFIX']
    app = web.Application([
        (prefix, Page),
        (url_path_join(prefix, 'api/table'), Table),
        (url_path_join(prefix, 'api/results'), Results),
        (url_path_join(prefix, 'oauth_callback'), HubOAuthCallbackHandler),
    ], cookie_secret=secrets.token_bytes(32))
    address = urlsplit(os.environ['JUPYTERHUB_SERVICE_URL'])

    async def forever() -> None:
        app.listen(address.port or 80, address.hostname or '127.0.0.1')
        await asyncio.Event().wait()

    asyncio.run(forever())


if __name__ == '__main__':
    sys.exit(main())
