"""RobotViewNode: subscribes to the kit's servo joints, IMU and camera and pushes them to the
robot view page over owl_web's WebSocket; publishes the page's "hold_imu" / "level" commands to
the simulated IMU's true_orientation."""

from __future__ import annotations

import threading
from typing import Any

from geometry_msgs.msg import Quaternion
from olive_sim.imu_node import DEFAULT_NAMESPACE as IMU_NAMESPACE
from olive_sim.module_node import node_name
from owl_web.server import Subscription, WebServer
from rclpy.node import Node
from rclpy.qos import qos_profile_sensor_data
from sensor_msgs.msg import CompressedImage, Imu, JointState

from robot_view.kit_state import hold_imu_orientation, joint_position, level_orientation

SERVOS = ('pan', 'tilt')
IMU_TOPIC = f'/olive/imu/{IMU_NAMESPACE}/imu'
TRUE_ORIENTATION_TOPIC = f"/{node_name('imu', IMU_NAMESPACE)}/true_orientation"
CAMERA_TOPIC = '/olive/camera/eye/image/compressed'


class RobotViewNode(Node):

    def __init__(self, server: WebServer) -> None:
        super().__init__('robot_view')
        self._lock = threading.Lock()
        self._state: dict[str, Any] = {'pan': None, 'tilt': None, 'imu': None}
        self._kit_watchers: set[Subscription] = set()
        self._camera_watchers: set[Subscription] = set()
        self._frames = 0
        for servo in SERVOS:
            self.create_subscription(JointState, f'/olive/servo/{servo}/joint',
                                     lambda message, servo=servo: self._on_joint(servo, message), 10)
        # sensor data QoS (best effort) matches both reliable and best-effort publishers
        self.create_subscription(Imu, IMU_TOPIC, self._on_imu, qos_profile_sensor_data)
        self.create_subscription(CompressedImage, CAMERA_TOPIC, self._on_frame, qos_profile_sensor_data)
        self.true_orientation = self.create_publisher(Quaternion, TRUE_ORIENTATION_TOPIC, 10)
        server.channel('kit', self._watch_kit, self._kit_watchers.discard)
        server.channel('camera', self._watch_camera, self._camera_watchers.discard)
        server.command('hold_imu', lambda arguments: self._publish(hold_imu_orientation(arguments)))
        server.command('level', lambda arguments: self._publish(level_orientation(arguments)))

    def _publish(self, orientation: tuple[float, float, float, float]) -> None:
        x, y, z, w = orientation
        self.true_orientation.publish(Quaternion(x=x, y=y, z=z, w=w))

    def _watch_kit(self, watcher: Subscription) -> None:
        with self._lock:
            self._kit_watchers.add(watcher)
            state = dict(self._state)
        watcher.send(state)

    def _watch_camera(self, watcher: Subscription) -> None:
        with self._lock:
            self._camera_watchers.add(watcher)

    def _push_state(self) -> None:
        with self._lock:
            state = dict(self._state)
            watchers = list(self._kit_watchers)
        for watcher in watchers:
            watcher.send(state)

    def _on_joint(self, servo: str, message: JointState) -> None:
        position = joint_position(list(message.name), list(message.position), f'{servo}_joint')
        if position is None:
            return
        with self._lock:
            self._state[servo] = position
        self._push_state()

    def _on_imu(self, message: Imu) -> None:
        q = message.orientation
        with self._lock:
            self._state['imu'] = [q.x, q.y, q.z, q.w]
        self._push_state()

    def _on_frame(self, message: CompressedImage) -> None:
        with self._lock:
            self._frames += 1
            number = self._frames
            watchers = list(self._camera_watchers)
        if not watchers:
            return
        data = bytes(message.data)
        content_type = 'image/png' if message.format.lower().startswith('png') else 'image/jpeg'
        for watcher in watchers:
            watcher.send_binary({'content_type': content_type, 'frame': number}, data)
