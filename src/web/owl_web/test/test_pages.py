"""The pages folder (owl_web.pages): entries, the catalogue and the front door's list, without a server."""

import os
import stat

import pytest
from owl_web import pages
from owl_web.pages import Page


def test_a_page_needs_a_mount_that_can_be_a_path_segment():
    assert Page('servo-pan', 'servo pan', 'ros2 launch olive_sim owl_kit.launch.py').mount == 'servo-pan'
    for mount in ('api', 'lib', 'owl', 'static', 'ws', 'Servo', 'servo pan', '-servo', '', 'a/b', 'x' * 64):
        with pytest.raises(ValueError, match='cannot be a page'):
            Page(mount, 'a page', 'start it')


@pytest.mark.parametrize(('data', 'error'), [
    ([], 'not a JSON object'),
    ({'mount': 'rqt', 'title': 'rqt'}, "'start' must be a string"),
    ({'mount': 'rqt', 'title': 'rqt', 'start': 'rqt', 'colour': 'red'}, "unknown key 'colour'"),
    ({'mount': 'rqt', 'title': 'rqt', 'start': 'rqt', 'pid': 'one'}, "'pid' must be a number"),
    ({'mount': 'RQT', 'title': 'rqt', 'start': 'rqt'}, 'cannot be a page'),
])
def test_a_malformed_entry_says_what_is_wrong(data, error):
    with pytest.raises(ValueError, match=error):
        Page.from_json(data)


def test_an_entry_is_removed_only_by_the_server_that_wrote_it(tmp_path):
    old = Page('servo-pan', 'servo pan', 'launch', '10.42.0.8', 'http://127.42.0.8:8042/', os.getpid())
    pages.register(old, tmp_path)
    moved = Page('servo-pan', 'servo pan', 'launch', '10.42.0.18', 'http://127.42.0.18:8042/', os.getpid())
    pages.register(moved, tmp_path)  # the module moved: its new server registers before the old one stops
    pages.unregister(old, tmp_path)
    assert pages.registered(tmp_path) == {'servo-pan': moved}
    pages.unregister(moved, tmp_path)
    assert pages.registered(tmp_path) == {}


def test_the_list_keeps_the_catalogues_order_and_says_which_run(tmp_path):
    catalogue = [Page('robot-view', 'robot view', 'ros2 launch robot_view robot_view.launch.py'),
                 Page('rqt', 'rqt', 'rqt'),
                 Page('servo-pan', 'servo pan', 'ros2 launch olive_sim owl_kit.launch.py', '10.42.0.8')]
    pages.write_catalogue(catalogue, tmp_path)
    pages.register(Page('rqt', 'rqt', '', url='http://127.0.0.1:8093/', pid=os.getpid()), tmp_path)
    killed = Page('servo-pan', 'servo pan', 'launch', '10.42.0.8', 'http://127.42.0.8:8042/', 999_999_999)
    pages.register(killed, tmp_path)  # killed without a word: its process is gone
    pages.register(Page('my-page', 'my page', 'python my_page.py', url='http://127.0.0.1:9000/',
                        pid=os.getpid()), tmp_path)
    (tmp_path / 'page-broken.json').write_text('{"mount": "broken"')  # not JSON: skipped, and said
    (tmp_path / 'page-odd.json').write_text('{"mount": "odd", "title": 3, "start": ""}')
    logged = []
    states = pages.page_states(tmp_path, answering=lambda url: url != 'http://127.0.0.1:9000/',
                               log=logged.append)
    assert [(s.page.mount, s.running) for s in states] == [
        ('robot-view', False), ('rqt', True), ('servo-pan', False), ('my-page', False)]
    assert states[1].page.start == 'rqt'  # an entry without a start command gets the catalogue's
    assert states[1].as_json() == {'mount': 'rqt', 'title': 'rqt', 'running': True, 'path': 'rqt/',
                                   'url': 'http://127.0.0.1:8093/', 'address': '', 'start': 'rqt'}
    assert states[2].as_json()['url'] == ''  # a stopped page offers no address to open
    assert logged == ['ignoring page-broken.json: not a JSON object',
                      "ignoring page-odd.json: 'title' must be a string"]


def test_the_folder_must_be_private_to_its_user(tmp_path):
    folder = tmp_path / 'pages'
    assert pages.private_folder(folder) == folder
    assert stat.S_IMODE(folder.stat().st_mode) == 0o700
    folder.chmod(0o777)  # as another user's folder in /tmp could be
    with pytest.raises(pages.PagesError, match='is not a private folder of yours'):
        pages.register(Page('rqt', 'rqt', 'rqt'), folder)
    assert not list(folder.iterdir())


def test_the_folder_follows_the_environment(tmp_path):
    assert pages.pages_dir({'OWL_PAGES_DIR': '/x/pages'}) == pages.Path('/x/pages')
    assert pages.pages_dir({'XDG_RUNTIME_DIR': str(tmp_path)}) == tmp_path / 'owl-kit-lab-pages'
    assert pages.pages_dir({}).name == f'owl-kit-lab-pages-{os.getuid()}'


@pytest.mark.parametrize('port', ['http', '-1', '65536', ' 80'])
def test_a_front_door_port_that_is_not_one_is_refused(tmp_path, port):
    with pytest.raises(ValueError, match=f"OWL_FRONT_DOOR_PORT must be a port number 0..65535, got '{port}'"):
        pages.ensure_front_door(tmp_path, {'OWL_FRONT_DOOR_PORT': port})
    assert pages.front_door_record(tmp_path) is None
