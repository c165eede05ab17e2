"""The Owl Kit as data: which modules, their names, addresses, pages, topics and limits.

The simulator starts the kit from this description, and the tools that talk to the kit
(robot_view, `owl network`) read it here, so none of them needs the simulator's node code.
Plain Python: no ROS import.
"""

from __future__ import annotations

import ipaddress
from dataclasses import dataclass, field
from typing import Any

# The course's first IMU: x + the 13-digit serial number (a Unix time in ms).
IMU_NAMESPACE = 'x1684267976913'
CAMERA_NAMESPACE = 'eye'  # the course's camera (section 4.5)
WEB_PORT = 8042  # of every simulated module's page (a real module's is 80, which needs root)
# A servo's PID gains accept 0 up to these (servo_sim's parameters, robot_view's sliders).
GAIN_LIMITS = {'kp': 100.0, 'ki': 1000.0, 'kd': 10.0}


def node_name(module_type: str, namespace: str) -> str:
    """The node name of a module: olive_<type>_<namespace>_dcm_srv, as on a real module."""
    return f'olive_{module_type}_{namespace}_dcm_srv'


def page_host(address: str) -> str:
    """The loopback address the page of the module at address answers at: 10.42.0.8 -> 127.42.0.8.

    Linux routes all of 127.0.0.0/8 to the loopback interface, so each simulated module's page
    gets an address of its own without root; ValueError for anything but a dotted IPv4 address.
    """
    _, b, c, d = ipaddress.IPv4Address(address).packed
    return f'127.{b}.{c}.{d}'


def topic(module_type: str, namespace: str, name: str) -> str:
    """The absolute name of a module's topic or service: /olive/<type>/<namespace>/<name>, as the course's."""
    return f'/olive/{module_type}/{namespace}/{name}'


def servo_topic(servo: str, name: str) -> str:
    """A servo's topic or service by its namespace ('pan', 'tilt'), e.g. 'joint', 'setTorqueEnable'."""
    return topic('servo', servo, name)


def goal_topic(servo: str) -> str:
    """The topic that takes a servo's position goals (std_msgs/msg/Float32, rad)."""
    return servo_topic(servo, 'goal/position')


def joint_topic(servo: str) -> str:
    """The servo's JointState topic."""
    return servo_topic(servo, 'joint')


IMU_TOPIC = topic('imu', IMU_NAMESPACE, 'imu')
CAMERA_TOPIC = topic('camera', CAMERA_NAMESPACE, 'image/compressed')
GESTURE_TOPIC = topic('camera', CAMERA_NAMESPACE, 'tpu/gesture')  # the camera's gesture app (section 4.7)

COMMON_TOPICS = ('led', 'status', 'switch', 'temperature')
# Topic names and types per module type, as `ros2 topic list -t` shows them in the course.
MODULE_TOPICS = {
    'imu': {'imu': 'sensor_msgs/msg/Imu', 'magnetometer': 'sensor_msgs/msg/MagneticField'},
    'servo': {'goal/position': 'std_msgs/msg/Float32', 'joint': 'sensor_msgs/msg/JointState',
              'joint/diagnostics': 'diagnostic_msgs/msg/DiagnosticStatus'},
    'camera': {'image/camera_info': 'sensor_msgs/msg/CameraInfo',
               'image/compressed': 'sensor_msgs/msg/CompressedImage',
               'imu': 'sensor_msgs/msg/Imu', 'magnetometer': 'sensor_msgs/msg/MagneticField'},
}
COMMON_TYPES = {'led': 'std_msgs/msg/Bool', 'status': 'diagnostic_msgs/msg/DiagnosticStatus',
                'switch': 'std_msgs/msg/Bool', 'temperature': 'sensor_msgs/msg/Temperature'}


@dataclass(frozen=True)
class KitModule:
    """One module of the kit: its type, namespace, executable, address and parameters of its own."""

    module_type: str
    namespace: str
    executable: str
    address: str  # the module's IP address in the course's set-up (sections 4.3.2 to 4.5)
    own_parameters: dict[str, Any] = field(default_factory=dict)

    @property
    def parameters(self) -> dict[str, Any]:
        """The module's parameters in the kit: its own and its address."""
        return {**self.own_parameters, 'address': self.address}

    @property
    def node(self) -> str:
        """The module's node name, olive_<type>_<namespace>_dcm_srv."""
        return node_name(self.module_type, self.namespace)

    def page_url(self, port: int | str = WEB_PORT) -> str:
        """Where the module's web page answers while its address is the kit's."""
        return f'http://{page_host(self.address)}:{port}/'

    def page(self) -> dict[str, str]:
        """The module's page for the front door (module_page's name, mount and start)."""
        return module_page(self.module_type, self.namespace, self.address)

    def topics(self) -> dict[str, str]:
        """Absolute topic name -> type of everything the module offers (position mode for servos)."""
        names = {**MODULE_TOPICS[self.module_type], **COMMON_TYPES}
        return {topic(self.module_type, self.namespace, name): names[name] for name in sorted(names)}


# The tilt servo carries the camera (about 80 g plus the L-bracket) 4 cm off its axis, and its
# range is what the vendor's demos use for the head.
OWL_KIT = (
    KitModule('imu', IMU_NAMESPACE, 'imu_sim', '10.42.0.20'),
    KitModule('servo', 'pan', 'servo_sim', '10.42.0.8', {'namespace': 'pan', 'min_position': -1.5708,
                                                         'max_position': 1.5708}),
    KitModule('servo', 'tilt', 'servo_sim', '10.42.0.9', {'namespace': 'tilt', 'load_mass': 0.12,
                                                          'load_offset': 0.04, 'min_position': -1.3,
                                                          'max_position': 0.9}),
    KitModule('camera', CAMERA_NAMESPACE, 'camera_sim', '10.42.0.10', {'namespace': CAMERA_NAMESPACE}),
)
# Each servo's goal range in the kit (its min_position, max_position), by namespace: pan, tilt.
SERVO_RANGES = {m.namespace: (m.own_parameters['min_position'], m.own_parameters['max_position'])
                for m in OWL_KIT if m.module_type == 'servo'}
# The red ball of the simulated scene (olive_sim's scene:=ball, section 4.6), in the camera's RGB: the
# simulator draws it, and the demo and the tests look for it in the camera's pictures.
BALL_COLOUR = (215, 20, 28)  # clearly red: hue ~358 deg, saturation 0.91, value 0.84
# The modules' subnet (a module's factory address is 10.42.0.7) and the student's PC on it.
KIT_SUBNET = '10.42.0.0/24'
STUDENT_ADDRESS = '10.42.0.1'


# The tools' pages on 127.0.0.1 and their default ports (each takes --port to choose another). The
# front door (owl_web's, port 8090) serves every page of the kit under one address besides.
RQT_PORT = 8093
ROBOT_VIEW_PORT = 8091
WINDOWS_PORT = 8092
KIT_LAUNCH = 'ros2 launch olive_sim owl_kit.launch.py'
# mount under the front door -> (title, the command that starts the page)
TOOL_PAGES = {
    'robot-view': ('robot view', 'ros2 launch robot_view robot_view.launch.py'),
    'rqt': ('rqt', 'rqt'),
    'windows': ('windows', 'owl windows'),
}


def tool_page(mount: str) -> dict[str, str]:
    """A tool's page for the front door: mount, title, start (owl_web.pages.Page's fields)."""
    title, start = TOOL_PAGES[mount]
    return {'mount': mount, 'title': title, 'start': start}


def module_page(module_type: str, namespace: str, address: str) -> dict[str, str]:
    """A module's page for the front door: at /<type>-<namespace>/, with the module's course address."""
    return {'mount': f'{module_type}-{namespace}'.lower(), 'title': f'{module_type} {namespace}',
            'start': KIT_LAUNCH, 'address': address}


def page_catalogue(modules: tuple[KitModule, ...] = OWL_KIT) -> list[dict[str, str]]:
    """Every page of the kit and its tools, in the front door's order: the tools', then each module's."""
    return [tool_page(mount) for mount in TOOL_PAGES] + [module.page() for module in modules]


def address_table(port: int | str = WEB_PORT, modules: tuple[KitModule, ...] = OWL_KIT) -> str:
    """The modules' addresses and web pages, printed when the kit starts."""
    rows = [('MODULE', 'ADDRESS', 'WEB PAGE')]
    rows += [(f'{m.module_type} {m.namespace}', m.address, m.page_url(port)) for m in modules]
    widths = [max(len(row[i]) for row in rows) for i in range(3)]
    return '\n'.join('  '.join(cell.ljust(width) for cell, width in zip(row, widths, strict=True)).rstrip()
                     for row in rows)


def topic_table(modules: tuple[KitModule, ...] = OWL_KIT) -> str:
    """A short table of the kit's modules and topics, printed when the kit starts."""
    rows = [('MODULE', 'NODE', 'TOPIC', 'TYPE')]
    for module in modules:
        for index, (topic, type_name) in enumerate(module.topics().items()):
            label = f'{module.module_type} {module.namespace}' if index == 0 else ''
            rows.append((label, module.node if index == 0 else '', topic, type_name))
    widths = [max(len(row[i]) for row in rows) for i in range(4)]
    return '\n'.join('  '.join(cell.ljust(width) for cell, width in zip(row, widths, strict=True)).rstrip()
                     for row in rows)
