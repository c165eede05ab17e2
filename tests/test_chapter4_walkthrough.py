"""Chapter 4 as a student works through it, from a fresh workspace to every project running.

A fresh workspace, `ros2 pkg create`, the scripts written as the course describes them, package.xml
and setup.py edits, `rosdep install`, `colcon build`, then every project run with
`ros2 run`/`ros2 launch` against the simulated kit, with and without a display.

The student's code below is written from the course's bullet points, not from our reference
solutions, so what it shows is that a course reader's own code works here. It is Jazzy-correct
where Jazzy differs from the course's Humble: Ctrl-C may end rclpy.spin with
ExternalShutdownException instead of KeyboardInterrupt, so both are caught; and a node that calls
the torque service after Ctrl-C keeps ROS up with SignalHandlerOptions.NO.
"""

import os
import signal
import textwrap
from collections.abc import Iterator
from pathlib import Path

import pytest
from ros_harness import RosHarness, wait_for_messages, wait_until
from sensor_msgs.msg import JointState
from std_msgs.msg import Float32
from student_workspace import shell
from turtlesim.msg import Pose

HEADLESS = {'DISPLAY': None, 'WAYLAND_DISPLAY': None}

IMU_TURTLE = '''
import math

import rclpy
from rclpy.executors import ExternalShutdownException
from geometry_msgs.msg import Quaternion, Twist
from rclpy.node import Node
from sensor_msgs.msg import Imu


class ImuTurtle(Node):

    def __init__(self):
        super().__init__('imu_turtle')
        self.declare_parameter('speed', 1.0)
        self.declare_parameter('imu_topic', '/olive/imu/x1684267976913/imu')
        self.orientation = Quaternion()
        self.subscription = self.create_subscription(
            Imu, self.get_parameter('imu_topic').value, self.imu_callback, 10)
        self.publisher = self.create_publisher(Twist, '/turtle1/cmd_vel', 10)

    def quaternion_to_euler(self, q):
        roll = math.atan2(2 * (q.w * q.x + q.y * q.z), 1 - 2 * (q.x ** 2 + q.y ** 2))
        pitch = math.asin(max(-1.0, min(1.0, 2 * (q.w * q.y - q.z * q.x))))
        yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y ** 2 + q.z ** 2))
        return roll, pitch, yaw

    def imu_callback(self, msg):
        self.orientation = msg.orientation
        roll, pitch, yaw = self.quaternion_to_euler(self.orientation)
        twist = Twist()
        twist.linear.x = pitch * self.get_parameter('speed').value
        twist.angular.z = yaw
        self.publisher.publish(twist)


def main(args=None):
    rclpy.init(args=args)
    imu_turtle = ImuTurtle()
    try:
        rclpy.spin(imu_turtle)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    imu_turtle.destroy_node()
    rclpy.try_shutdown()
'''

TURTLE_LAUNCH = '''
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        Node(package='turtlesim', executable='turtlesim_node'),
        Node(package='olive_imu', executable='imu_turtle', parameters=[{'speed': 2.0}]),
    ])
'''

# Section 4.4's three projects share the torque services; the student's scripts each call them.
TORQUE = '''
    def call(self, client):
        while not client.wait_for_service(timeout_sec=1.0):
            self.get_logger().info('service not available')
        future = client.call_async(Trigger.Request())
        rclpy.spin_until_future_complete(self, future, timeout_sec=5.0)
'''

CONTROL_SERVO = '''
import math

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.signals import SignalHandlerOptions
from std_msgs.msg import Float32
from std_srvs.srv import Trigger


class ControlServo(Node):

    def __init__(self):
        super().__init__('control_servo')
        self.enable = self.create_client(Trigger, '/olive/servo/pan/setTorqueEnable')
        self.disable = self.create_client(Trigger, '/olive/servo/pan/setTorqueDisable')
        self.publisher = self.create_publisher(Float32, '/olive/servo/pan/goal/position', 10)
        self.x = 0.0
        self.call(self.enable)
        self.timer = self.create_timer(0.01, self.publish_goal)
''' + TORQUE + '''
    def publish_goal(self):
        msg = Float32()
        msg.data = math.sin(self.x)
        self.x += 0.01
        self.publisher.publish(msg)


def main(args=None):
    rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)
    control_servo = ControlServo()
    try:
        rclpy.spin(control_servo)
    except (KeyboardInterrupt, ExternalShutdownException):
        control_servo.call(control_servo.disable)
    control_servo.destroy_node()
    rclpy.try_shutdown()
'''

KEYBOARD_SERVOS = '''
import pygame
import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.signals import SignalHandlerOptions
from std_msgs.msg import Float32
from std_srvs.srv import Trigger


class KeyboardServos(Node):

    def __init__(self):
        super().__init__('keyboard_servos')
        pygame.init()
        self.screen = pygame.display.set_mode((300, 200))
        pygame.display.set_caption('keyboard servos')
        self.pan_publisher = self.create_publisher(Float32, '/olive/servo/pan/goal/position', 10)
        self.tilt_publisher = self.create_publisher(Float32, '/olive/servo/tilt/goal/position', 10)
        servos = ('pan', 'tilt')
        self.enable = [self.create_client(Trigger, f'/olive/servo/{s}/setTorqueEnable') for s in servos]
        self.disable = [self.create_client(Trigger, f'/olive/servo/{s}/setTorqueDisable') for s in servos]
        for client in self.enable:
            self.call(client)
        self.pan = 0.0
        self.tilt = 0.0
        self.timer = self.create_timer(0.01, self.publish_goals)
''' + TORQUE + '''
    def publish_goals(self):
        pygame.event.pump()
        keys = pygame.key.get_pressed()
        if keys[pygame.K_LEFT]:
            self.pan += 0.01
        if keys[pygame.K_RIGHT]:
            self.pan -= 0.01
        if keys[pygame.K_UP]:
            self.tilt -= 0.01
        if keys[pygame.K_DOWN]:
            self.tilt += 0.01
        self.pan = max(-1.5, min(1.5, self.pan))
        self.tilt = max(-1.2, min(0.8, self.tilt))
        self.pan_publisher.publish(Float32(data=self.pan))
        self.tilt_publisher.publish(Float32(data=self.tilt))


def main(args=None):
    rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)
    keyboard_servos = KeyboardServos()
    try:
        rclpy.spin(keyboard_servos)
    except (KeyboardInterrupt, ExternalShutdownException):
        for client in keyboard_servos.disable:
            keyboard_servos.call(client)
    keyboard_servos.destroy_node()
    rclpy.try_shutdown()
'''

IMU_CONTROL_ROBOT = '''
import math

import rclpy
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node
from rclpy.signals import SignalHandlerOptions
from sensor_msgs.msg import Imu
from std_msgs.msg import Float32
from std_srvs.srv import Trigger


class ImuControlRobot(Node):

    def __init__(self):
        super().__init__('imu_control_robot')
        self.pan_publisher = self.create_publisher(Float32, '/olive/servo/pan/goal/position', 10)
        self.tilt_publisher = self.create_publisher(Float32, '/olive/servo/tilt/goal/position', 10)
        for servo in ('pan', 'tilt'):
            self.call(self.create_client(Trigger, f'/olive/servo/{servo}/setTorqueEnable'))
        self.subscription = self.create_subscription(
            Imu, '/olive/imu/x1684267976913/imu', self.imu_callback, 10)
''' + TORQUE + '''
    def imu_callback(self, msg):
        q = msg.orientation
        pitch = math.asin(max(-1.0, min(1.0, 2 * (q.w * q.y - q.z * q.x))))
        yaw = math.atan2(2 * (q.w * q.z + q.x * q.y), 1 - 2 * (q.y ** 2 + q.z ** 2))
        self.pan_publisher.publish(Float32(data=max(-1.5, min(1.5, yaw))))
        self.tilt_publisher.publish(Float32(data=max(-1.2, min(0.8, pitch))))


def main(args=None):
    rclpy.init(args=args, signal_handler_options=SignalHandlerOptions.NO)
    imu_control_robot = ImuControlRobot()
    try:
        rclpy.spin(imu_control_robot)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    imu_control_robot.destroy_node()
    rclpy.try_shutdown()
'''

# Section 4.5's project, shared with tests/test_headless_windows.py.
DISPLAY_CAMERA = (Path(__file__).parent / 'student_scripts' / 'student_display_camera.py').read_text()

CAMERA_LAUNCH = '''
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        Node(package='olive_servo', executable='imu_control_robot'),
        Node(package='olive_camera', executable='display_camera'),
    ])
'''

# package -> (ros2 pkg create --dependencies, extra package.xml keys, scripts, launch files)
PACKAGES = {
    'olive_imu': (['rclpy', 'sensor_msgs', 'geometry_msgs'], [],
                  {'imu_turtle': IMU_TURTLE}, {'turtle_imu.launch.py': TURTLE_LAUNCH}),
    'olive_servo': (['rclpy', 'std_msgs', 'std_srvs', 'sensor_msgs'], ['python3-pygame'],
                    {'control_servo': CONTROL_SERVO, 'keyboard_servos': KEYBOARD_SERVOS,
                     'imu_control_robot': IMU_CONTROL_ROBOT}, {}),
    'olive_camera': (['rclpy', 'sensor_msgs', 'cv_bridge'], ['python3-opencv'],
                     {'display_camera': DISPLAY_CAMERA}, {'robot_camera.launch.py': CAMERA_LAUNCH}),
}


def write_package(src: Path, name: str) -> None:
    """What the course has the student do after `ros2 pkg create`: scripts, entry points, keys."""
    dependencies, keys, scripts, launch_files = PACKAGES[name]
    created = shell(src, f'ros2 pkg create {name} --build-type ament_python --dependencies '
                         + ' '.join(dependencies))
    assert created.returncode == 0, created.stderr
    package = src / name
    for script, code in scripts.items():
        (package / name / f'{script}.py').write_text(textwrap.dedent(code).lstrip())
    setup_py = (package / 'setup.py').read_text()
    entry_points = ''.join(f"\n            '{s} = {name}.{s}:main'," for s in scripts)
    setup_py = setup_py.replace("'console_scripts': [", "'console_scripts': [" + entry_points)
    if launch_files:
        (package / 'launch').mkdir()
        for file_name, code in launch_files.items():
            (package / 'launch' / file_name).write_text(textwrap.dedent(code).lstrip())
        setup_py = setup_py.replace(
            "('share/' + package_name, ['package.xml']),",
            "('share/' + package_name, ['package.xml']),\n"
            "        ('share/' + package_name + '/launch', glob('launch/*.launch.py')),")
        setup_py = 'from glob import glob\n' + setup_py
    (package / 'setup.py').write_text(setup_py)
    manifest = (package / 'package.xml').read_text()
    extra = ''.join(f'  <exec_depend>{key}</exec_depend>\n' for key in keys)
    (package / 'package.xml').write_text(manifest.replace('  <test_depend>', extra + '  <test_depend>', 1))


@pytest.fixture(scope='module')
def workspace(tmp_path_factory):
    """The student's workspace: created, rosdep-checked and built as chapter 4 says."""
    workspace = tmp_path_factory.mktemp('student_ws')
    (workspace / 'src').mkdir()
    for name in PACKAGES:
        write_package(workspace / 'src', name)
    # Were a key missing, pip must fail here rather than change the venv.
    env = dict(os.environ, PIP_NO_INDEX='1', PIP_TARGET=str(workspace / 'pip_target'))
    rosdep = shell(workspace, 'rosdep install -i --from-paths src -y', env=env)
    assert rosdep.returncode == 0, rosdep.stdout + rosdep.stderr
    assert '#All required rosdeps installed successfully' in rosdep.stdout, rosdep.stdout + rosdep.stderr
    build = shell(workspace, 'colcon build')
    assert build.returncode == 0, build.stdout + build.stderr
    return workspace


def student(ros, workspace: Path, command: str, label: str, env: dict | None = None):
    """A student's `ros2 run`/`ros2 launch` in the workspace's overlay, in the test's domain."""
    setup = workspace / 'install' / 'local_setup.bash'
    return ros.command(['bash', '-c', f'source {setup} && exec {command}'], label=label, env=env,
                       cwd=str(workspace))


@pytest.fixture(scope='module')
def running_kit() -> Iterator[RosHarness]:
    """`ros2 launch olive_sim owl_kit.launch.py`, once for the module's projects on the kit."""
    harness = RosHarness()
    try:
        harness.command(['ros2', 'launch', 'olive_sim', 'owl_kit.launch.py'], label='kit')
        harness.probe.wait_for_node('olive_camera_eye_dcm_srv', timeout=40)
        yield harness
    finally:
        harness.close()


@pytest.fixture
def kit(running_kit: RosHarness) -> Iterator[RosHarness]:
    """The module's running kit, as a student's terminal sees it; what a test starts is stopped after it.

    Each project below starts on the kit as the one before left it (a servo where it was, its torque
    as the last node left it), as in a student's session.
    """
    with running_kit.turn() as harness:
        yield harness


def positions(ros, servo: str) -> list:
    return ros.probe.collect(JointState, f'/olive/servo/{servo}/joint')


def moved(joints: list, at_least: float) -> bool:
    values = [j.position[0] for j in joints]
    return bool(values) and max(values) - min(values) >= at_least


def stop(process, launch: bool = False) -> str:
    """Ctrl-C, and the process must end with code 0 and no traceback.

    A terminal's Ctrl-C reaches the whole process group. `ros2 launch` without a terminal on stdin
    is non-interactive and forwards SIGINT to its nodes itself (as upstream does), so a launch gets
    the signal alone: its nodes get one SIGINT either way, as at a terminal.
    """
    if launch:
        os.kill(process.pid, signal.SIGINT)
    else:
        process.send_signal(signal.SIGINT)
    code = process.wait(15)
    assert code == 0, process.tail()
    assert 'Traceback' not in process.output, process.output
    return process.output


def test_imu_turtle_and_its_launch_file_drive_the_turtle(ros, workspace):
    ros.run('olive_sim', 'imu_sim')  # the scripted motion: pitch and yaw sweep
    poses = ros.probe.collect(Pose, '/turtle1/pose', 7)
    launch = student(ros, workspace, 'ros2 launch olive_imu turtle_imu.launch.py', 'student launch',
                     env=HEADLESS)
    wait_for_messages(poses, 10, timeout=40, what='turtle poses')
    wait_until(lambda: abs(poses[-1].x - poses[0].x) + abs(poses[-1].y - poses[0].y) > 0.5, 30,
               'the turtle to move')
    stop(launch, launch=True)


@pytest.mark.whole_kit
def test_control_servo_moves_the_pan_servo_in_a_sine(kit, workspace):
    joints = positions(kit, 'pan')
    node = student(kit, workspace, 'ros2 run olive_servo control_servo', 'student control_servo')
    wait_until(lambda: moved(joints, 0.5), 40, 'the pan servo to swing')
    stop(node)


@pytest.mark.whole_kit
def test_imu_control_robot_turns_both_servos(kit, workspace):
    pan, tilt = positions(kit, 'pan'), positions(kit, 'tilt')
    node = student(kit, workspace, 'ros2 run olive_servo imu_control_robot', 'student imu_control_robot')
    wait_until(lambda: moved(pan, 0.3) and moved(tilt, 0.3), 40, 'both servos to follow the IMU')
    stop(node)


@pytest.mark.whole_kit
def test_keyboard_servos_without_a_display_says_so_in_one_line_and_keeps_running(kit, workspace):
    goals = kit.probe.collect(Float32, '/olive/servo/pan/goal/position')
    node = student(kit, workspace, 'ros2 run olive_servo keyboard_servos', 'student keyboard_servos',
                   env=HEADLESS)
    wait_for_messages(goals, 100, timeout=40, what='pan goals')
    notices = [line for line in node.lines if 'no display' in line]
    assert len(notices) == 1, node.output
    assert node.running()
    stop(node)


@pytest.mark.whole_kit
def test_keyboard_servos_with_a_display_turns_the_pan_servo_on_the_left_arrow(kit, workspace, x_display):
    goals = kit.probe.collect(Float32, '/olive/servo/pan/goal/position')
    node = student(kit, workspace, 'ros2 run olive_servo keyboard_servos', 'student keyboard_servos',
                   env=x_display.env())
    window = x_display.wait_for_window(name='keyboard servos', timeout=40)
    wait_for_messages(goals, 10, timeout=40, what='pan goals')
    x_display.press(window, 'Left', 1.0)
    wait_until(lambda: goals[-1].data > 0.3, 10, f'the pan goal to grow (last {goals[-1].data})')
    assert 'no display' not in node.output
    stop(node)


@pytest.mark.whole_kit
def test_display_camera_without_a_display_says_so_in_one_line_and_keeps_showing_frames(kit, workspace):
    node = student(kit, workspace, 'ros2 run olive_camera display_camera', 'student display_camera',
                   env=HEADLESS)
    node.wait_for(r'60 frames shown', timeout=40)
    assert len([line for line in node.lines if 'no display' in line]) == 1, node.output
    stop(node)


@pytest.mark.whole_kit
def test_display_camera_with_a_display_opens_its_window(kit, workspace, x_display):
    node = student(kit, workspace, 'ros2 run olive_camera display_camera', 'student display_camera',
                   env=x_display.env())
    x_display.wait_for_window(name='^Olive Camera$', timeout=40)
    node.wait_for(r'30 frames shown', timeout=40)
    assert 'no display' not in node.output
    stop(node)


@pytest.mark.whole_kit
def test_the_camera_launch_file_runs_the_robot_and_the_camera(kit, workspace):
    pan = positions(kit, 'pan')
    launch = student(kit, workspace, 'ros2 launch olive_camera robot_camera.launch.py', 'student launch',
                     env=HEADLESS)
    launch.wait_for(r'30 frames shown', timeout=60)
    wait_until(lambda: moved(pan, 0.3), 40, 'the pan servo to follow the IMU')
    stop(launch, launch=True)
