"""RobotViewNode: the kit's servos, IMU and camera on the robot view page, and the page's commands.

It subscribes to the kit's servo joints and goals, IMU and camera and pushes them to the robot
view page over owl_web's WebSocket (the model's state, the live plots, the camera's frames, the
servos' gains and torque); it carries out the page's commands: "hold_imu" / "level" on the
simulated IMU's true_orientation, and "set_gains", "torque" and "goal" on the servos.
"""

from __future__ import annotations

import datetime
import json
import math
import threading
import time
from functools import partial
from typing import Any

from diagnostic_msgs.msg import DiagnosticStatus
from geometry_msgs.msg import Quaternion
from olive_kit.description import (
    CAMERA_NAMESPACE,
    CAMERA_TOPIC,
    IMU_TOPIC,
    goal_topic,
    joint_topic,
    node_name,
    servo_topic,
)
from owl_common import quaternion
from owl_common.graph import full_node_name
from owl_common.polled_subscription import PolledSubscription
from owl_web.codec import ApiError
from owl_web.server import Subscription, WebServer
from rcl_interfaces.msg import Parameter, ParameterEvent, ParameterType, ParameterValue
from rcl_interfaces.srv import GetParameters, SetParameters
from rclpy.client import Client
from rclpy.node import Node
from rclpy.qos import DurabilityPolicy, QoSProfile, qos_profile_sensor_data
from rclpy.time import Time
from sensor_msgs.msg import CompressedImage, Imu, JointState
from std_msgs.msg import Float32, String
from std_srvs.srv import Trigger

from robot_view.controls import (
    GAINS,
    SERVOS,
    ball_request,
    control_limits,
    gains_request,
    goal_request,
    servo_node,
    torque_request,
)
from robot_view.kit_state import (
    TRUE_ORIENTATION_TOPIC,
    first_presence_due,
    goal_outcome,
    hold_imu_orientation,
    joint_position,
    kit_presence,
    level_orientation,
    servo_unavailable,
    silences,
)
from robot_view.plot_window import PlotWindow, PushCursor, sample_time
from robot_view.recording import BagRecording, record_request, recordings_folder

CAMERA_NODE = f"/{node_name('camera', CAMERA_NAMESPACE)}"
SCENE_TOPIC = f'{CAMERA_NODE}/scene'  # the simulated camera's ball and person (scene:=ball or person)
PLOT_SERIES = (*(f'{servo}_{what}' for servo in SERVOS for what in ('goal', 'position', 'effort')),
               'roll', 'pitch', 'yaw')
PLOT_PUSH_EVERY = 0.1  # s: ten batches a second keep a 10 s plot moving smoothly
SERVICE_TIMEOUT = 3.0  # s for a servo to answer a command's service call
DISCOVERY_WAIT = 2.0  # s a command waits for its service to be discovered before saying it is missing
RESEND_EVERY = 1.0  # s: see _call
ASK_GAINS_EVERY = 1.0  # s between two questions to a servo whose gains are not known yet
LOOK_AT_GRAPH_EVERY = 1.0  # s between two looks at which modules run and what steers them
LISTEN_FOR_SILENCE_EVERY = 0.25  # s: a module's silence shows within SILENT_AFTER and this
JOINT_PUSH_WAIT = 0.02  # s: a joint's state waits this long at most for a push it can go with


class RobotViewNode(Node):
    """The robot_view node: serves the page's channels and commands on server (see the module's text)."""

    def __init__(self, server: WebServer) -> None:
        super().__init__('robot_view')
        self._started = time.monotonic()
        self._lock = threading.Lock()
        # 'kit' is what runs of the kit and what steers it (kit_presence), None until the first look
        # 'silent': module -> whole seconds since its last message, for those silent (kit_state.silences)
        # 'recording': the folder of the bag being recorded (the Record button), None when not recording
        self._state: dict[str, Any] = {'pan': None, 'tilt': None, 'imu': None, 'scene': None, 'kit': None,
                                       'silent': {}, 'recording': None}
        self._recording: BagRecording | None = None
        self._recording_lock = threading.Lock()  # one start or stop at a time (each takes seconds)
        self._heard: dict[str, float] = {}  # module -> when its last message came (time.monotonic)
        self._pushed = 0.0  # when the kit state was last pushed (time.monotonic)
        self._kit_watchers: set[Subscription] = set()
        self._camera_watchers: set[Subscription] = set()
        self._plot_watchers: dict[Subscription, PushCursor] = {}
        self._servo_watchers: set[Subscription] = set()
        self._frames = 0
        self._plots = PlotWindow(PLOT_SERIES, held=[f'{servo}_goal' for servo in SERVOS])
        # what the page's controls show: each servo's gains and torque (None until known)
        self._servos: dict[str, dict[str, Any]] = {
            servo: {**dict.fromkeys(GAINS), 'torque': None} for servo in SERVOS}
        self._goal_publishers = {}
        self._goals: dict[str, PolledSubscription] = {}
        self._torque_clients: dict[tuple[str, bool], Client] = {}
        self._set_parameters: dict[str, Client] = {}
        self._get_parameters: dict[str, Client] = {}
        for servo in SERVOS:
            self.create_subscription(JointState, joint_topic(servo), partial(self._on_joint, servo), 10)
            # Every goal on the topic is plotted, the page's and any other node's. Taken just before
            # each joint message is handled, not by executor callbacks: imu_control_robot sends
            # 100 goals a second per servo, and waking the executor for each cost robot_view 6 % of
            # a core (29 % instead of 23 %, with a page open); a goal is at most one joint period
            # (10 ms) late in the plot, within its 20 ms bucket.
            self._goals[servo] = PolledSubscription(
                self, Float32, goal_topic(servo), partial(self._on_goal, servo), 10, info=True)
            self.create_subscription(DiagnosticStatus, servo_topic(servo, 'joint/diagnostics'),
                                     partial(self._on_diagnostics, servo), 10)
            self._goal_publishers[servo] = self.create_publisher(Float32, goal_topic(servo), 10)
            for enabled, service in ((True, 'setTorqueEnable'), (False, 'setTorqueDisable')):
                self._torque_clients[servo, enabled] = self.create_client(
                    Trigger, servo_topic(servo, service))
            node = servo_node(servo)
            self._set_parameters[servo] = self.create_client(SetParameters, f'{node}/set_parameters')
            self._get_parameters[servo] = self.create_client(GetParameters, f'{node}/get_parameters')
        # gains set from anywhere (`ros2 param set`, the page) show on the page
        self.create_subscription(ParameterEvent, '/parameter_events', self._on_parameter_event, 100)
        # sensor data QoS (best effort) matches both reliable and best-effort publishers
        self.create_subscription(Imu, IMU_TOPIC, self._on_imu, qos_profile_sensor_data)
        self.create_subscription(CompressedImage, CAMERA_TOPIC, self._on_frame, qos_profile_sensor_data)
        self.true_orientation = self.create_publisher(Quaternion, TRUE_ORIENTATION_TOPIC, 10)
        self.create_subscription(String, SCENE_TOPIC, self._on_scene,
                                 QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL))
        self._set_camera_parameters = self.create_client(SetParameters, f'{CAMERA_NODE}/set_parameters')
        self.create_timer(PLOT_PUSH_EVERY, self._push_plots)
        self._asking: dict[str, Any] = {}  # servo -> its unanswered question for its gains
        self.create_timer(ASK_GAINS_EVERY, self._ask_for_unknown_gains)
        self.create_timer(LOOK_AT_GRAPH_EVERY, self._look_at_graph)
        self.create_timer(LISTEN_FOR_SILENCE_EVERY, self._listen_for_silence)
        server.channel('kit', self._watch_kit, self._kit_watchers.discard)
        server.channel('camera', self._watch_camera, self._camera_watchers.discard)
        server.channel('plots', self._watch_plots, self._forget_plot_watcher)
        server.channel('servos', self._watch_servos, self._servo_watchers.discard)
        # a drag sends 50 of these a second, and a student sees each one's way to the IMU and back
        server.command('hold_imu', lambda arguments: self._publish(hold_imu_orientation(arguments)),
                       at_once=True)
        server.command('level', lambda arguments: self._publish(level_orientation(arguments)), at_once=True)
        server.command('set_gains', self._set_gains)
        server.command('torque', self._torque)
        server.command('goal', self._goal)
        server.command('place_ball', self._place_ball)
        server.command('record', self._record)

    # ---- the page's commands (each runs in a worker thread of the web server) ---------------

    def _publish(self, orientation: tuple[float, float, float, float]) -> None:
        x, y, z, w = orientation
        self.true_orientation.publish(Quaternion(x=x, y=y, z=z, w=w))

    def _goal(self, arguments: dict[str, Any]) -> dict[str, Any]:
        """Publish the goal; what came of it: 'ignored' when the servo says its torque is off, else 'sent'.

        Whether a sent goal is reached the page sees in the servo's joint.
        """
        servo, position = goal_request(arguments)
        self._require_running(servo)
        self._goal_publishers[servo].publish(Float32(data=position))
        with self._lock:
            torque = self._servos[servo]['torque']
            steered_by = self._state['kit']['steered'][servo] if self._state['kit'] else []
        return goal_outcome(servo, torque, steered_by)

    def _record(self, arguments: dict[str, Any]) -> dict[str, Any]:
        """Start `ros2 bag record` of the plotted topics, or stop it: the folder, or what the bag holds."""
        on = record_request(arguments)
        with self._recording_lock:
            if on == (self._recording is not None):
                raise ApiError(409, f"already recording into {self._recording.folder}: stop it first"
                               if self._recording is not None else 'not recording: there is nothing to stop')
            if on:
                self._recording = BagRecording(recordings_folder(), datetime.datetime.now())
                result: dict[str, Any] = {'folder': str(self._recording.folder)}
            else:
                assert self._recording is not None
                recording, self._recording = self._recording, None
                result = recording.stop()
        with self._lock:
            self._state['recording'] = result['folder'] if on else None
        self._push_state()
        return result

    def destroy_node(self) -> None:
        """Finish a recording still running, so its bag is whole; then destroy the node as rclpy does."""
        with self._recording_lock:
            if self._recording is not None:
                self._recording.process.stop()
                self._recording = None
        for goals in self._goals.values():
            goals.destroy()
        super().destroy_node()

    def _require_running(self, servo: str) -> None:
        """An ApiError saying why a command to the servo cannot act, when it sends no joint states."""
        with self._lock:
            why = servo_unavailable(servo, self._state['silent'].get(servo), servo in self._heard)
        if why is not None:
            raise ApiError(409, why)

    def _torque(self, arguments: dict[str, Any]) -> None:
        servo, enabled = torque_request(arguments)
        self._require_running(servo)
        client = self._torque_clients[servo, enabled]
        response = self._call(client, Trigger.Request(), f'servo {servo}')
        if not response.success:
            raise ApiError(409, f'{client.srv_name} refused: {response.message}')
        self._update_servo(servo, torque=enabled)

    def _set_gains(self, arguments: dict[str, Any]) -> None:
        servo, gains = gains_request(arguments)
        self._require_running(servo)
        request = SetParameters.Request(parameters=double_parameters(gains))
        response = self._call(self._set_parameters[servo], request, f'servo {servo}')
        refusals = [f'{name}: {result.reason}' for name, result in zip(gains, response.results, strict=False)
                    if not result.successful]
        if refusals:
            raise ApiError(409, f"{servo_node(servo)} refused {'; '.join(refusals)}")
        self._update_servo(servo, **gains)

    def _place_ball(self, arguments: dict[str, Any]) -> None:
        azimuth, elevation = ball_request(arguments)
        places = {'ball_azimuth': azimuth, 'ball_elevation': elevation}
        request = SetParameters.Request(parameters=double_parameters(places))
        response = self._call(self._set_camera_parameters, request, 'the camera (scene:=ball)')
        refusals = [result.reason for result in response.results if not result.successful]
        if refusals:
            raise ApiError(409, f"the camera refused to put the ball there: {'; '.join(refusals)}")

    def _call(self, client: Client, request: Any, what: str) -> Any:
        """A service's response, waited for in this (web worker) thread while the executor spins.

        A missing (not discovered within DISCOVERY_WAIT: one that has just started, or a robot_view
        that has, may not be yet) or silent service is one ApiError line. Every request here is
        idempotent, so it goes out again when no answer came within RESEND_EVERY: a server that has
        not discovered this client yet drops the request or its response.
        """
        if not client.wait_for_service(timeout_sec=DISCOVERY_WAIT):
            raise ApiError(503, f'{client.srv_name} is not available (is {what} running?)')
        deadline = time.monotonic() + SERVICE_TIMEOUT
        while (left := deadline - time.monotonic()) > 0:
            answered = threading.Event()
            future = client.call_async(request)
            future.add_done_callback(lambda _, answered=answered: answered.set())
            if answered.wait(min(RESEND_EVERY, left)):
                return future.result()
            client.remove_pending_request(future)
        raise ApiError(504, f'{client.srv_name} did not answer within {SERVICE_TIMEOUT:g} s')

    # ---- the page's channels ------------------------------------------------------------------

    def _watch_kit(self, watcher: Subscription) -> None:
        with self._lock:
            self._kit_watchers.add(watcher)
            state = dict(self._state)
        watcher.send(state)

    def _watch_camera(self, watcher: Subscription) -> None:
        with self._lock:
            self._camera_watchers.add(watcher)

    def _watch_plots(self, watcher: Subscription) -> None:
        cursor = PushCursor()
        with self._lock:
            self._plot_watchers[watcher] = cursor
            batch = cursor.batch(self._plots)  # the window so far, at once
        if batch is not None:
            watcher.send(batch)

    def _forget_plot_watcher(self, watcher: Subscription) -> None:
        with self._lock:
            self._plot_watchers.pop(watcher, None)

    def _watch_servos(self, watcher: Subscription) -> None:
        with self._lock:
            self._servo_watchers.add(watcher)
            message = self._servo_message()
        watcher.send(message)

    def _ask_for_unknown_gains(self) -> None:
        """Ask each servo whose gains are not known yet for them; never waits (it runs on the executor).

        A servo that started before robot_view announced its gains on /parameter_events before
        robot_view listened.
        """
        for servo, client in self._get_parameters.items():
            with self._lock:
                known = self._servos[servo]['kp'] is not None
            if known or not client.service_is_ready():
                continue
            unanswered = self._asking.pop(servo, None)
            if unanswered is not None:  # lost in discovery (see _call): ask again
                client.remove_pending_request(unanswered)
            future = client.call_async(GetParameters.Request(names=list(GAINS)))
            self._asking[servo] = future
            future.add_done_callback(lambda done, servo=servo: self._on_gains(servo, done))

    def _on_gains(self, servo: str, future: Any) -> None:
        if self._asking.get(servo) is future:
            del self._asking[servo]
        values = future.result().values if future.result() is not None else []
        if len(values) == len(GAINS) and all(v.type == ParameterType.PARAMETER_DOUBLE for v in values):
            self._update_servo(servo, **{name: v.double_value for name, v in zip(GAINS, values, strict=True)})

    def _update_servo(self, servo: str, **values: Any) -> None:
        with self._lock:
            if all(self._servos[servo].get(key) == value for key, value in values.items()):
                return
            self._servos[servo].update(values)
            message = self._servo_message()
            watchers = list(self._servo_watchers)
        for watcher in watchers:
            watcher.send(message)

    def _servo_message(self) -> dict[str, Any]:
        """The servos channel's update: each servo's gains and torque, and the controls' limits."""
        return {'state': {servo: dict(values) for servo, values in self._servos.items()},
                'limits': control_limits()}

    def _look_at_graph(self) -> None:
        """Which of the kit's modules run, and what steers the IMU and the servos; pushed when it changes."""
        presence = kit_presence(
            publishers={topic: self.count_publishers(topic) for topic in (
                IMU_TOPIC, CAMERA_TOPIC, *map(joint_topic, SERVOS), *map(goal_topic, SERVOS))},
            subscribers={TRUE_ORIENTATION_TOPIC: self.count_subscribers(TRUE_ORIENTATION_TOPIC)},
            steering={servo: self._goal_publisher_nodes(servo) for servo in SERVOS})
        with self._lock:
            if self._state['kit'] == presence:
                return
            since_start = time.monotonic() - self._started
            if self._state['kit'] is None and not first_presence_due(presence, since_start):
                return
            self._state['kit'] = presence
        self._push_state()

    def _goal_publisher_nodes(self, servo: str) -> list[str]:
        """The nodes other than this one that publish the servo's goals, by their full names."""
        own = self.get_fully_qualified_name()
        names = (full_node_name(info.node_namespace, info.node_name)
                 for info in self.get_publishers_info_by_topic(goal_topic(servo)))
        return [name for name in names if name != own]

    def _listen_for_silence(self) -> None:
        """Which modules have sent nothing for SILENT_AFTER s or more; pushed when it changes."""
        with self._lock:
            silent = silences(self._heard, time.monotonic())
            if silent == self._state['silent']:
                return
            self._state['silent'] = silent
        self._push_state()

    def _push_plots(self) -> None:
        for goals in self._goals.values():  # a servo that publishes no joint still shows its goals
            goals.poll()
        with self._lock:
            batches = [(watcher, cursor.batch(self._plots, last_sent=not watcher.pending()))
                       for watcher, cursor in self._plot_watchers.items()]
        for watcher, batch in batches:
            if batch is not None:
                watcher.send(batch)

    def _push_state(self) -> None:
        with self._lock:
            state = dict(self._state)
            watchers = list(self._kit_watchers)
            self._pushed = time.monotonic()
        for watcher in watchers:
            watcher.send(state)

    def _plot(self, values: dict[str, float], stamp_ns: int | None) -> None:
        """Plot samples at the time they were measured or sent (see plot_window's text)."""
        if not values:
            return
        with self._lock:
            self._plots.add(sample_time(stamp_ns, time.time()), values)

    # ---- ROS callbacks ------------------------------------------------------------------------

    def _on_joint(self, servo: str, message: JointState) -> None:
        self._goals[servo].poll()  # the goals that came before this joint message
        names = list(message.name)
        position = joint_position(names, list(message.position), f'{servo}_joint')
        if position is None:
            return
        effort = joint_position(names, list(message.effort), f'{servo}_joint')
        samples = {f'{servo}_position': position}
        if effort is not None:
            samples[f'{servo}_effort'] = effort
        with self._lock:
            self._state[servo] = position
            self._heard[servo] = time.monotonic()
            # A joint's state goes with the IMU's next push (100 a second) unless none came lately:
            # pushing at each of the two joints' 100 messages a second too tripled the page's work.
            due = time.monotonic() - self._pushed >= JOINT_PUSH_WAIT
        self._plot(finite(samples), Time.from_msg(message.header.stamp).nanoseconds)
        if due:
            self._push_state()

    def _on_goal(self, servo: str, message: Float32, info: dict[str, Any]) -> None:
        self._plot(finite({f'{servo}_goal': float(message.data)}), info.get('source_timestamp'))

    def _on_diagnostics(self, servo: str, message: DiagnosticStatus) -> None:
        torque = next((value.value for value in message.values if value.key == 'torque_enabled'), None)
        if torque in ('true', 'false'):
            self._update_servo(servo, torque=torque == 'true')

    def _on_parameter_event(self, event: ParameterEvent) -> None:
        servo = next((s for s in SERVOS if event.node == servo_node(s)), None)
        if servo is None:
            return
        gains = {p.name: p.value.double_value for p in [*event.new_parameters, *event.changed_parameters]
                 if p.name in GAINS and p.value.type == ParameterType.PARAMETER_DOUBLE}
        if gains:
            self._update_servo(servo, **gains)

    def _on_imu(self, message: Imu) -> None:
        q = message.orientation
        with self._lock:
            self._state['imu'] = [q.x, q.y, q.z, q.w]
            self._heard['imu'] = time.monotonic()
        euler = quaternion.usable_euler((q.x, q.y, q.z, q.w))
        if euler is not None:
            roll, pitch, yaw = euler
            self._plot({'roll': roll, 'pitch': pitch, 'yaw': yaw},
                       Time.from_msg(message.header.stamp).nanoseconds)
        self._push_state()

    def _on_scene(self, message: String) -> None:
        try:
            scene = json.loads(message.data)
        except json.JSONDecodeError:
            return  # not the simulated camera's: nothing to draw
        with self._lock:
            self._state['scene'] = scene if isinstance(scene, dict) else None
        self._push_state()

    def _on_frame(self, message: CompressedImage) -> None:
        with self._lock:
            self._frames += 1
            number = self._frames
            self._heard['camera'] = time.monotonic()
            watchers = list(self._camera_watchers)
        if not watchers:
            return
        data = bytes(message.data)
        content_type = 'image/png' if message.format.lower().startswith('png') else 'image/jpeg'
        for watcher in watchers:
            watcher.send_binary({'content_type': content_type, 'frame': number}, data)


def double_parameters(values: dict[str, float]) -> list[Parameter]:
    """A SetParameters request's parameters: each value as a double."""
    return [Parameter(name=name,
                      value=ParameterValue(type=ParameterType.PARAMETER_DOUBLE, double_value=value))
            for name, value in values.items()]


def finite(samples: dict[str, float]) -> dict[str, float]:
    """The samples a plot can draw: a NaN or infinity from another node is left out."""
    return {name: value for name, value in samples.items() if math.isfinite(value)}

