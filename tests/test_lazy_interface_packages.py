"""scripts/lazy_interface_packages.py: a msg/srv/action module loads each type on its first use."""

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest
import setup_scripts

lazy = setup_scripts.load('lazy_interface_packages')

# Plain Python processes (no ROS graph): no slot needed.
pytestmark = pytest.mark.no_processes

GENERATED = ('from my_msgs.msg._point import Point  # noqa: F401\n'
             'from my_msgs.msg._heavy_scan import HeavyScan  # noqa: F401\n')


def interface_package(site: Path) -> Path:
    """my_msgs with two message modules as rosidl writes them (here: plain classes), in site."""
    msg = site / 'my_msgs' / 'msg'
    msg.mkdir(parents=True)
    (site / 'my_msgs' / '__init__.py').write_text('')
    (msg / '_point.py').write_text('class Point:\n    x = 1.0\n')
    (msg / '_heavy_scan.py').write_text(
        'import my_heavy_dependency  # noqa: F401\n' + lazy.NUMPY_IMPORT + '\n\n'
        'class HeavyScan:\n    def __init__(self):\n        self.ranges = numpy.zeros(3)\n')
    (site / 'my_heavy_dependency.py').write_text('')
    (msg / '__init__.py').write_text(GENERATED)
    return msg / '__init__.py'


def python(site: Path, code: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, '-c', code], capture_output=True, text=True, timeout=30,
                          env={'PYTHONPATH': str(site)})


def test_a_type_loads_its_module_when_first_asked_for_and_the_package_names_every_type(tmp_path):
    init = interface_package(tmp_path)
    assert lazy.main([str(tmp_path)]) == 0
    assert init.read_text().startswith(lazy.MARKER)
    for source in (init, init.parent / '_heavy_scan.py'):  # compiled, as the wheels are
        assert Path(importlib.util.cache_from_source(str(source))).is_file()
    ran = python(tmp_path, 'import sys\n'
                 'from my_msgs.msg import Point\n'
                 'print(Point.x, "my_heavy_dependency" in sys.modules)\n'
                 'import my_msgs.msg as m\n'
                 'print(sorted(m.__all__), "HeavyScan" in dir(m), "my_heavy_dependency" in sys.modules)\n'
                 'from my_msgs.msg import *\n'
                 'print(HeavyScan.__name__, m.HeavyScan is HeavyScan, "my_heavy_dependency" in sys.modules)\n'
                 'print("numpy" in sys.modules, type(HeavyScan().ranges).__name__, "numpy" in sys.modules)\n'
                 'import my_msgs.msg._heavy_scan as module\n'
                 'print(module.numpy is sys.modules["numpy"])\n'
                 'try:\n    m.Nothing\nexcept AttributeError as error:\n    print(error)\n')
    assert ran.stdout.splitlines() == [
        '1.0 False',
        "['HeavyScan', 'Point'] True False",
        'HeavyScan True True',
        'False ndarray True',  # numpy at the first message that needs it
        'True',  # and then in the stand-in's place
        "module 'my_msgs.msg' has no attribute 'Nothing'",
    ], ran.stderr


def test_an_init_that_is_not_rosidls_list_of_imports_is_left_alone(tmp_path):
    init = interface_package(tmp_path)
    lazy.main([str(tmp_path)])
    rewritten = init.read_text()
    assert lazy.main([str(tmp_path)]) == 0  # already lazy
    assert init.read_text() == rewritten
    edited = GENERATED + 'VERSION = 2\n'
    init.write_text(edited)
    lazy.main([str(tmp_path)])
    assert init.read_text() == edited
    foreign = 'from other_msgs.msg._point import Point  # noqa: F401\n'  # another package's module
    init.write_text(foreign)
    lazy.main([str(tmp_path)])
    assert init.read_text() == foreign


@pytest.mark.parametrize('argv', [[], ['/no/such/folder'], ['.', '/no/such/folder']])
def test_wrong_arguments_are_one_usage_line(argv, capsys):
    assert lazy.main(argv) == 2
    error = capsys.readouterr().err
    assert error.startswith('usage: lazy_interface_packages.py FOLDER...')
    assert error.count('\n') == 1


def test_setup_made_the_wheels_interfaces_lazy_and_a_servo_module_needs_no_numpy():
    """A servo's types and its parameter services' without numpy; an Imu's covariances load it.

    Each is still a working ROS type (serialized and read back). A service's type support brings
    service_msgs' ServiceEventInfo, whose client_gid is a fixed-size array.
    """
    ran = subprocess.run([sys.executable, '-c', (
        'import sys\n'
        'from rclpy.serialization import serialize_message, deserialize_message\n'
        'from sensor_msgs.msg import JointState, Imu\n'
        'from rcl_interfaces.srv import SetParameters\n'
        'SetParameters.__class__.__import_type_support__()\n'
        'print(SetParameters.Event.__name__, "service_msgs.msg._service_event_info" in sys.modules)\n'
        'data = serialize_message(JointState(name=["pan_joint"], position=[1.5]))\n'
        'print(deserialize_message(data, JointState).position[0], "numpy" in sys.modules)\n'
        'imu = deserialize_message(serialize_message(Imu(orientation_covariance=[0.5] * 9)), Imu)\n'
        'print(imu.orientation_covariance[8], "numpy" in sys.modules)\n')],
        capture_output=True, text=True, timeout=60)
    assert ran.stdout.splitlines() == ['SetParameters_Event True', '1.5 False', '0.5 True'], ran.stderr
