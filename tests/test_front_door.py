"""The front door with the whole kit, the robot view, rqt and `owl windows` running, in Chromium.

The browser may reach the front door's origin only (every other host and port is aborted, WebSockets
included), as a student's browser on Windows reaches a WSL2 machine's 127.0.0.1, and opens every page
from the index, doing its main job there: a module's System Status and Debug GUI (and a Network
Settings move, which the front door follows), the robot view's live IMU and a servo goal, rqt's node
graph, turtlesim's window on `owl windows`. Then the same behind a class server's path prefix
(tests/prefix_proxy.py, which forwards as jupyter-server-proxy does), with the proxy's public origin
trusted explicitly. One world serves every test here; a test that stops a page starts it again.
docs/screenshots/front_door*.png are made here.
"""

from __future__ import annotations

import http.client
import json
import re
from collections.abc import Iterator
from functools import partial
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit

import pytest
from desktop import NO_DISPLAY
from owl_web.pages import port_answers
from prefix_proxy import PrefixProxy
from ros_harness import RosHarness, wait_until
from sensor_msgs.msg import JointState
from test_robot_view import drag
from web_harness import PROXY_HOST, BrowserPage, check_module_pages, free_port, open_from_index

pytestmark = pytest.mark.whole_kit  # the whole kit with the robot view's 3D page
MODULES = {'imu-x1684267976913': '10.42.0.20', 'servo-pan': '10.42.0.8', 'servo-tilt': '10.42.0.9',
           'camera-eye': '10.42.0.10'}
PAGES = ['robot-view', 'rqt', 'windows', *MODULES]
TIMEOUT = 60.0  # s for the kit and the pages to start on a loaded 2-core machine


class World:
    """The kit with robot_view (robot_view.launch.py), rqt, owl windows and turtlesim, at one front door."""

    def __init__(self, ros: RosHarness, windows: Path, proxy: PrefixProxy) -> None:
        self.ros = ros
        self.windows = windows
        ros.env.update({'OWL_FRONT_DOOR': 'on', 'OWL_FRONT_DOOR_PORT': '0',
                        'OWL_TRUSTED_ORIGINS': f'http://{PROXY_HOST}:{proxy.port}'})
        # The module pages on a port of the world's own: another test's kit (or this world started
        # again in another worker, as the module-scoped fixture may be) holds the default 8042.
        self.launch = ros.command(['ros2', 'launch', 'robot_view', 'robot_view.launch.py', 'port:=0',
                                   f'web_port:={free_port()}'], label='robot_view.launch')
        rqt = ros.command(['rqt', '--port', '0', '--no-browser'], label='rqt')
        self.turtlesim = ros.run('turtlesim', 'turtlesim_node',
                                 env={**NO_DISPLAY, 'OWL_WINDOWS_DIR': str(windows)})
        self.start_windows()
        opened = rqt.wait_for(r'^rqt: open (http://127\.0\.0\.1:\d+/)rqt/ in a browser', TIMEOUT)
        self.door = opened[0].group(1)
        self.launch.wait_for(rf'robot_view: open {re.escape(self.door)}robot-view/ in a browser', TIMEOUT)
        self.launch.wait_for(rf'through the front door: {re.escape(self.door)}[a-z0-9-]+/$', TIMEOUT, count=4)

    def start_windows(self) -> None:
        self.owl_windows = self.ros.command(['owl', 'windows', '--port', '0', '--folder', str(self.windows)],
                                            label='owl windows')
        self.owl_windows.wait_for(r'^owl windows: open http://127\.0\.0\.1:\d+/windows/ in a browser',
                                  TIMEOUT)

    @property
    def door_port(self) -> int:
        return int(urlsplit(self.door).port or 0)


@pytest.fixture(scope='module')
def proxy() -> Iterator[PrefixProxy]:
    started = PrefixProxy()
    try:
        yield started
    finally:
        started.close()


@pytest.fixture(scope='module')
def world(proxy, tmp_path_factory) -> Iterator[World]:
    ros = RosHarness()
    try:
        yield World(ros, tmp_path_factory.mktemp('windows'), proxy)
    finally:
        ros.close()


def only_origin(page: BrowserPage, base: str) -> list[str]:
    """Let the page reach base's origin only: every other request and WebSocket is aborted, and listed."""
    origin = urlsplit(base)[:2]
    aborted: list[str] = []

    def request(route: Any) -> None:
        if urlsplit(route.request.url)[:2] == origin:
            route.continue_()
        else:
            aborted.append(route.request.url)
            route.abort()

    def websocket(route: Any) -> None:
        aborted.append(route.url)
        route.close()

    page.route('**/*', request)
    # Only the other origins' WebSockets are routed: a routed one that is let through passes every
    # message through Playwright's client (the camera's 30 frames/s), which delayed a 10-step drag
    # by 23 s to minutes. The ones of the origin go straight to the server.
    scheme, netloc = origin
    own = re.escape(f"{'wss' if scheme == 'https' else 'ws'}://{netloc}/")
    page.route_web_socket(re.compile(f'^(?!{own})'), websocket)
    return aborted


def check_index(page: BrowserPage, base: str, screenshot: str) -> None:
    page.goto(base)
    page.wait_for_function(f'() => document.querySelectorAll("li.running").length === {len(PAGES)}',
                           timeout=20_000)
    mounts = page.eval_on_selector_all('li.page', '(items) => items.map((item) => item.dataset.mount)')
    assert mounts == PAGES
    for mount, address in MODULES.items():
        assert f'module {address} in the course' in page.inner_text(f'li[data-mount="{mount}"]')
    page.screenshot_to(screenshot)


def check_robot_view(page: BrowserPage, base: str, joints: list[JointState]) -> None:
    """The live IMU turned with the mouse, and a goal that moves the pan servo."""
    open_from_index(page, base, 'robot-view')
    page.wait_for_function('() => window.robotView.imu !== null && window.robotView.servos '
                           '&& window.robotView.servos.pan.kp !== null', timeout=30_000)
    before = page.evaluate('JSON.stringify(window.robotView.imu)')
    drag(page, 40)
    page.wait_for_function(f'() => JSON.stringify(window.robotView.imu) !== {json.dumps(before)}',
                           timeout=10_000)
    row = '#servo-controls tr[data-servo=pan]'
    if not page.is_checked(f'{row} input.torque'):
        page.click(f'{row} input.torque')
    goal = 0.0 if joints and abs(joints[-1].position[0]) > 0.5 else 1.57  # away from where it is
    page.click(f'{row} button.goal[data-goal="{goal:g}"]')
    wait_until(lambda: joints and abs(joints[-1].position[0] - goal) < 0.05, 15, f'the pan servo at {goal}')


def check_rqt(page: BrowserPage, base: str) -> None:
    open_from_index(page, base, 'rqt')
    page.wait_for_selector('#graph-svg g[data-id="/robot_view"]', timeout=20_000)
    page.wait_for_selector('#graph-svg g[data-id="/olive/servo/pan/joint"]', timeout=20_000)
    # The kit's graph (a long chain of layers) wraps into rows, and fitted to the page its labels stay
    # readable (it used to be one row drawn at 24-47 %, labels of 3-6 px); the rest scrolls.
    fit = page.text_content('#graph-zoom-level')
    zoom = re.match(r'(?:fit \()?(\d+) %', fit)
    assert zoom is not None, fit
    assert int(zoom.group(1)) >= 60, fit


def check_windows(page: BrowserPage, base: str) -> None:
    open_from_index(page, base, 'windows')
    page.wait_for_function('() => Number(document.querySelector(\'[data-window^="turtlesim"]\')'
                           '?.dataset.frames ?? 0) >= 1', timeout=20_000)


def test_every_page_opens_from_the_front_doors_index_and_does_its_main_job(world, page):
    aborted = only_origin(page, world.door)
    joints = world.ros.probe.collect(JointState, '/olive/servo/pan/joint')
    check_index(page, world.door, 'front_door')
    check_module_pages(page, world.door)
    check_robot_view(page, world.door, joints)
    page.screenshot_to('front_door_robot_view')
    check_rqt(page, world.door)
    check_windows(page, world.door)
    # A module that moves (Network Settings): the page stays at the front door and follows it, and back.
    open_from_index(page, world.door, 'servo-tilt')
    page.wait_for_function('() => window.modulePage.device !== null', timeout=20_000)
    for address in ('10.42.0.19', '10.42.0.9'):
        before = page.evaluate('window.modulePage.device.url')
        page.fill('input[name=address]', address)
        page.click('#network-save')
        page.wait_for_function(f'() => document.getElementById("title").textContent.endsWith("at {address}")',
                               timeout=15_000)
        assert page.url == f'{world.door}servo-tilt/'
        index = json.loads(fetch(world.door, 'api/pages')[2])
        own = next(entry['url'] for entry in index if entry['mount'] == 'servo-tilt')
        assert own.startswith(f"http://127.{address.split('.', 1)[1]}:")
        wait_until(partial(stopped_answering, before), 5, 'the old address to stop answering')
    page.forgive_server_away()  # the old address's socket, closed as the module moved
    assert aborted == []


def test_every_page_works_behind_a_class_servers_path_prefix(world, proxy, page):
    base = proxy.url('alice', world.door_port, PROXY_HOST)
    aborted = only_origin(page, base)
    joints = world.ros.probe.collect(JointState, '/olive/servo/pan/joint')
    check_index(page, base, 'front_door_prefix')
    check_module_pages(page, base)
    check_robot_view(page, base, joints)
    check_rqt(page, base)
    page.screenshot_to('front_door_prefix_rqt')
    check_windows(page, base)
    assert aborted == []
    # The front door trusts the proxy's origin because OWL_TRUSTED_ORIGINS says so; nothing else passes,
    # whatever a client writes about where it comes from.
    path = f'/user/alice/proxy/{world.door_port}/rqt/api/publishers'
    body = b'{"topic": "/chatter", "type": "std_msgs/msg/String", "rate": 1}'
    for forged in ({'Host': 'evil.test', 'X-Forwarded-Host': f'{PROXY_HOST}:{proxy.port}'},
                   {'Origin': 'http://evil.test', 'Forwarded': f'host={PROXY_HOST}:{proxy.port}'}):
        status, _, answer = fetch(f'http://127.0.0.1:{proxy.port}/', path.lstrip('/'), 'POST', body, forged)
        assert status == 403, answer
    assert json.loads(fetch(world.door, 'rqt/api/publishers')[2]) == []  # nothing was created


def test_a_page_that_stops_is_greyed_with_its_command_and_comes_back(world, page):
    page.goto(world.door)
    page.wait_for_selector('li.running[data-mount="windows"]', timeout=20_000)
    world.owl_windows.stop_cleanly()
    try:
        page.wait_for_selector('li.stopped[data-mount="windows"]', timeout=10_000)  # refreshed in place
        assert 'start it: owl windows' in page.inner_text('li[data-mount="windows"]')
        page.screenshot_to('front_door_stopped')
        status, _, answer = fetch(world.door, 'windows/')
        assert status == 503
        assert 'windows is not running; start it: owl windows' in answer.decode()
        status, _, answer = fetch(world.door, 'no-such-page/')
        assert status == 404
        assert all(f'data-mount="{mount}"' in answer.decode() for mount in PAGES)
    finally:
        world.start_windows()
    page.wait_for_selector('li.running[data-mount="windows"]', timeout=10_000)


def stopped_answering(url: str) -> bool:
    return not port_answers(url)


def fetch(base: str, path: str, method: str = 'GET', body: bytes | None = None,
          headers: dict[str, str] | None = None) -> tuple[int, dict[str, str], bytes]:
    parts = urlsplit(base)
    connection = http.client.HTTPConnection(parts.hostname or '127.0.0.1', parts.port, timeout=20)
    try:
        connection.request(method, parts.path + path, body=body, headers=headers or {})
        answer = connection.getresponse()
        return answer.status, dict(answer.getheaders()), answer.read()
    finally:
        connection.close()
