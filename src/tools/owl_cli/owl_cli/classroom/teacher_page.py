"""The teacher's page: each student, when they last worked, and their latest `owl check` results.

A JupyterHub service (`/services/owl-teacher/`), started by the hub with the hub's venv and this
package's folder on PYTHONPATH (this module and what it imports need only the standard library,
plus JupyterHub's own service library and tornado, which the hub's venv has). It runs as root, as
the hub does: each student's results sit in their private home (`owl check` keeps them, see
owl_cli.check_report.results_file). Who may open it is JupyterHub's to say: a service is open to
the accounts whose roles give access to it, which the admin role does and the default user role
does not, so the teacher (the hub's admin) gets the page and a student the hub's 403.

The page shows the class roll that `owl class serve` writes (ROLL in the state folder: the
students in the class list's order, and the course's sections with their checkable exercises),
one row per student, one column per section, and refreshes its table every few seconds.
"""

from __future__ import annotations

import html
import json
import pwd
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from owl_cli.check_report import read_latest, results_file

ROLL = 'class-roll.json'
SERVICE_NAME = 'owl-teacher'
REFRESH_SECONDS = 3


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


def home_of(name: str) -> Path | None:
    """The account's home folder, None when there is no such account."""
    try:
        return Path(pwd.getpwnam(name).pw_dir)
    except KeyError:
        return None


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

    results: each student's latest result per exercise (owl_cli.check_report.read_latest); activity:
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
        counts = {'passed': 0, 'failed': 0}
        for _, exercises in roll.sections:
            marks = []
            for exercise in exercises:
                record = mine.get(exercise)
                state = ('not-run' if record is None
                         else 'passed' if record.get('passed') is True else 'failed')
                counts[state] = counts.get(state, 0) + 1
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


def class_results(roll: Roll) -> dict[str, dict[str, dict[str, Any]]]:
    """Each student's latest results, read from their home (no account or no file: none)."""
    found: dict[str, dict[str, dict[str, Any]]] = {}
    for name in roll.students:
        home = home_of(name)
        found[name] = {} if home is None else read_latest(results_file({'HOME': str(home)}))
    return found


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
    import os
    import secrets
    from datetime import datetime
    from urllib.parse import urlsplit

    from jupyterhub.services.auth import HubOAuthCallbackHandler, HubOAuthenticated
    from jupyterhub.utils import url_path_join
    from tornado import web
    from tornado.httpclient import AsyncHTTPClient

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

    async def current_table() -> str:
        roll = Roll.from_json(roll_path.read_text())  # read at each refresh: a restart may change it
        return table_html(roll, class_results(roll), await activity(), time.time())

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

    prefix = os.environ['JUPYTERHUB_SERVICE_PREFIX']
    app = web.Application([
        (prefix, Page),
        (url_path_join(prefix, 'api/table'), Table),
        (url_path_join(prefix, 'oauth_callback'), HubOAuthCallbackHandler),
    ], cookie_secret=secrets.token_bytes(32))
    address = urlsplit(os.environ['JUPYTERHUB_SERVICE_URL'])

    async def forever() -> None:
        app.listen(address.port or 80, address.hostname or '127.0.0.1')
        await asyncio.Event().wait()

    asyncio.run(forever())


if __name__ == '__main__':
    sys.exit(main())
