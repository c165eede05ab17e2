"""The rqt node: the backend of the rqt page, on the ROS graph.

It answers the page's requests from the ROS graph, publishes, calls, subscribes, and pushes the
graph and image frames to the page over its WebSocket (owl_web).

Its methods are called from the web server's threads while rclpy spins the node in the main
thread; they take plain data (parsed JSON) and return plain data, raising ApiError for bad input.
"""

import os
import threading
import time
from dataclasses import dataclass, field
from typing import Any

from owl_common.graph import GraphQueries, endpoint_to_dict, is_hidden_name, matching_policies
from owl_web.codec import ApiError, boolean, check_keys, message_fields
from owl_web.graph import GraphChannel
from owl_web.server import Request, Subscription, WebServer
from rclpy.client import Client
from rclpy.exceptions import InvalidServiceNameException, InvalidTopicNameException
from rclpy.node import Node
from rclpy.publisher import Publisher
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy, qos_profile_sensor_data
from rosidl_runtime_py.get_interfaces import interface_index
from rosidl_runtime_py.set_message import FieldError, StampSetter, set_message_fields
from rosidl_runtime_py.utilities import InvalidType, canonical_type, import_type, type_name_of

from rqt_web import api_input
from rqt_web.images import ImageError, compressed_for_browser, raw_to_png
from rqt_web.interface_template import RosMessage, field_template
from rqt_web.topic_inspector import ArrivalRate, endpoint_summary, message_summary

IMAGE_TYPES = ('sensor_msgs/msg/Image', 'sensor_msgs/msg/CompressedImage')
PUBLISHER_KEYS = ('topic', 'type', 'rate', 'fields', 'enabled')
CALL_KEYS = ('service', 'type', 'request', 'timeout')
IMAGE_KEYS = ('topic',)
INSPECT_KEYS = ('topic',)
INSPECTOR_PUSH_EVERY = 0.2  # s: a message's fields at most five times a second
INSPECTOR_REFRESH = 1.0  # s between two pushes of a topic that sent nothing new (its rate, its endpoints)
DEFAULT_CALL_TIMEOUT = 10.0  # s
FIRST_FRAME_TIMEOUT = 5.0  # s before the page hears that no frame came yet


@dataclass
class MessagePublisher:
    """One row of Message Publisher: a message published at a rate while enabled."""

    id: int
    topic: str
    type_name: str
    rate: float
    enabled: bool
    fields: dict[str, Any]
    message: RosMessage
    stamps: list[StampSetter]
    publisher: Publisher
    timer: Any = None
    published: int = 0

    def as_dict(self) -> dict[str, Any]:
        """The row as the page shows it (JSON-ready): its settings, the message and how many went out."""
        return {'id': self.id, 'topic': self.topic, 'type': self.type_name, 'rate': self.rate,
                'enabled': self.enabled, 'fields': self.fields,
                'message': message_fields(self.message), 'published': self.published}


@dataclass
class InspectedTopic:
    """A topic the topic inspector watches: its subscription, the pages watching it, what came."""

    topic: str
    type_name: str
    subscription: Any = None
    watchers: set[Subscription] = field(default_factory=set)
    rate: ArrivalRate = field(default_factory=ArrivalRate)
    count: int = 0
    latest: Any = None  # the last message, converted only when pushed
    pushed: float = 0.0  # when the watchers were last told (time.monotonic)
    fresh: bool = False  # a message came since


@dataclass
class ImageFeed:
    """One image topic's subscription and the pages watching it (Image View)."""

    topic: str
    type_name: str
    subscription: Any = None
    watchers: set[Subscription] = field(default_factory=set)
    frames: int = 0
    started: float = field(default_factory=time.monotonic)
    latest: tuple[dict[str, Any], bytes] | None = None  # (frame header, image bytes)
    error: str | None = None  # what the watchers were last told instead of a frame


def _message_type(type_name: str, kind: str) -> Any:
    try:
        return import_type(type_name, kind)
    except InvalidType as error:
        raise ApiError(404, f"unknown {'message' if kind == 'msg' else 'service'} type: {error}") from None


def _filled(message: Any, values: Any, expand_stamps: bool = False) -> tuple[Any, list[Any]]:
    """(the message with the values set, the setters of its `header: auto`/`stamp: now` fields)."""
    try:
        stamps = set_message_fields(message, values, expand_header_auto=expand_stamps,
                                    expand_time_now=expand_stamps)
    except FieldError as error:
        raise ApiError(400, str(error)) from None
    return message, stamps


class RqtWebNode(Node):
    """The backend of the page: one node for all four plugins."""

    def __init__(self, server: WebServer) -> None:
        super().__init__(f'rqt_gui_py_node_{os.getpid()}')
        self._graph_queries = GraphQueries(self)
        self._state_lock = threading.Lock()
        self._message_publishers: dict[int, MessagePublisher] = {}
        self._next_publisher_id = 1
        self._service_clients: dict[tuple[str, Any], Client] = {}  # key: (name, service class)
        self._image_feeds: dict[str, ImageFeed] = {}
        self._inspected: dict[str, InspectedTopic] = {}
        self.create_timer(INSPECTOR_PUSH_EVERY, self._push_inspected_topics)
        self._silence_check = self.create_timer(1.0, self._report_silent_feeds)
        self._server = server
        self._add_routes(server)
        GraphChannel(self, server)
        server.channel('image', self.watch_images, self.stop_watching_images)
        server.channel('topic', self.inspect_topic, self.stop_inspecting)
        server.start()

    def _add_routes(self, server: WebServer) -> None:
        def names(entries: dict[str, list[str]]) -> list[dict[str, Any]]:
            return [{'name': name, 'types': types} for name, types in sorted(entries.items())]

        def change_publisher(request: Request) -> dict[str, Any]:
            return self.update_message_publisher(api_input.identifier(request.params['id']), request.json())

        def remove_publisher(request: Request) -> dict[str, Any]:
            publisher_id = api_input.identifier(request.params['id'])
            self.remove_message_publisher(publisher_id)
            return {'deleted': publisher_id}

        server.route('GET', '/api/topics', lambda request: names(self.topic_types()))
        server.route('GET', '/api/image_topics', lambda request: names(self.image_topic_types()))
        server.route('GET', '/api/services', lambda request: names(self.service_types()))
        server.route('GET', '/api/interface',
                     lambda request: self.interface(api_input.query_text(request.query, 'type')))
        server.route('GET', '/api/interfaces',
                     lambda request: self.interface_names(api_input.query_text(request.query, 'kind')))
        server.route('GET', '/api/publishers', lambda request: self.message_publishers())
        server.route('POST', '/api/publishers',
                     lambda request: (201, self.add_message_publisher(request.json())))
        server.route('PATCH', '/api/publishers/{id}', change_publisher)
        server.route('DELETE', '/api/publishers/{id}', remove_publisher)
        server.route('POST', '/api/call', lambda request: self.call_service(request.json()))

    def destroy_node(self) -> None:
        """Stop the web server, then destroy the node as rclpy does."""
        self._server.stop()
        super().destroy_node()

    # ---- graph -------------------------------------------------------------------------------

    def topic_types(self) -> dict[str, list[str]]:
        """Every topic of the graph with its types, hidden topics left out."""
        return {name: types for name, types in self._graph_queries.topic_names_and_types()
                if not is_hidden_name(name)}

    def service_types(self) -> dict[str, list[str]]:
        """Every service of the graph with its types, hidden services left out."""
        return {name: types for name, types in self._graph_queries.service_names_and_types()
                if not is_hidden_name(name)}

    @staticmethod
    def interface_names(kind: str) -> list[str]:
        """Every installed message ('msg') or service ('srv') type, for the pickers."""
        if kind not in ('msg', 'srv'):
            raise ApiError(400, f"kind must be 'msg' or 'srv', got {kind!r}")
        return sorted(f'{package}/{kind}/{name}' for package, kinds in interface_index().items()
                      for name in kinds[kind])

    def interface(self, type_name: str) -> dict[str, Any]:
        """Field templates of a message type or of a service type's request and response."""
        kinds = [part for part in ('msg', 'srv') if f'/{part}/' in type_name] or ['msg', 'srv']
        errors = []
        for kind in kinds:
            try:
                type_class = import_type(type_name, kind)
            except InvalidType as error:
                errors.append(str(error))
                continue
            if kind == 'msg':
                return {'type': canonical_type(type_name, kind), 'kind': kind,
                        'fields': field_template(type_class())}
            return {'type': canonical_type(type_name, kind), 'kind': kind,
                    'request': field_template(type_class.Request()),
                    'response': field_template(type_class.Response())}
        # 'pkg/Name' was tried as both kinds: say the reason that names a close type, if one does.
        reason = next((e for e in errors if 'did you mean' in e), errors[0])
        raise ApiError(404, f'unknown interface type: {reason}')

    # ---- Message Publisher ---------------------------------------------------------------------

    def message_publishers(self) -> list[dict[str, Any]]:
        """The rows of Message Publisher, in the order they were added (see MessagePublisher.as_dict)."""
        with self._state_lock:
            return [entry.as_dict() for entry in self._message_publishers.values()]

    def add_message_publisher(self, body: dict[str, Any]) -> dict[str, Any]:
        """Add a Message Publisher row from the page's request body and return it (as_dict).

        The type may be left out for a topic the graph knows with one type; a given one must match
        the topic's. The row publishes at its rate once enabled (off by default).
        """
        check_keys(body, PUBLISHER_KEYS, required=('topic',))
        topic = api_input.name(body['topic'], 'topic')
        rate = api_input.rate(body.get('rate', 1.0))
        enabled = boolean(body.get('enabled', False), 'enabled')
        values = api_input.fields(body.get('fields'), 'fields')
        given_type = api_input.optional_text(body.get('type'), 'type')
        topics = self.topic_types()
        existing = topics.get(topic)
        if given_type is None:
            given_type = api_input.single_type(topic, api_input.known_name(topic, topics, 'topic'), 'topic')
        message_class = _message_type(given_type, 'msg')
        type_name = type_name_of(message_class)
        if existing and type_name not in existing:
            raise ApiError(400, f"topic '{topic}' has type {', '.join(existing)}, not {type_name}")
        message, stamps = _filled(message_class(), values, expand_stamps=True)
        try:
            publisher = self.create_publisher(message_class, topic, 10)
        except InvalidTopicNameException as error:
            raise ApiError(400, f"invalid topic name '{topic}': {str(error).splitlines()[0]}") from None
        with self._state_lock:
            entry = MessagePublisher(self._next_publisher_id, topic, type_name, rate, enabled, values,
                                     message, stamps, publisher)
            self._next_publisher_id += 1
            self._message_publishers[entry.id] = entry
            self._start_timer(entry)
            return entry.as_dict()

    def update_message_publisher(self, publisher_id: int, body: dict[str, Any]) -> dict[str, Any]:
        """Change rate, fields (replacing the previous values) or enabled."""
        check_keys(body, ('rate', 'fields', 'enabled'))
        entry = self._message_publisher(publisher_id)
        rate = api_input.rate(body['rate']) if 'rate' in body else entry.rate
        enabled = boolean(body['enabled'], 'enabled') if 'enabled' in body else entry.enabled
        stamps: list[StampSetter] = []
        if 'fields' in body:
            values = api_input.fields(body['fields'], 'fields')
            message, stamps = _filled(type(entry.message)(), values, expand_stamps=True)
        with self._state_lock:
            if self._message_publishers.get(publisher_id) is not entry:
                raise self._unknown_publisher(publisher_id)  # removed meanwhile
            if 'fields' in body:
                entry.fields, entry.message, entry.stamps = values, message, stamps
            if rate != entry.rate or enabled != entry.enabled:
                entry.rate, entry.enabled = rate, enabled
                self.destroy_timer(entry.timer)
                self._start_timer(entry)
            return entry.as_dict()

    def remove_message_publisher(self, publisher_id: int) -> None:
        """Remove a Message Publisher row, its timer and its publisher; ApiError 404 for an unknown id."""
        with self._state_lock:
            entry = self._message_publishers.pop(publisher_id, None)
            if entry is None:
                raise self._unknown_publisher(publisher_id)
            self.destroy_timer(entry.timer)
            self.destroy_publisher(entry.publisher)

    def _message_publisher(self, publisher_id: int) -> MessagePublisher:
        with self._state_lock:
            if publisher_id not in self._message_publishers:
                raise self._unknown_publisher(publisher_id)
            return self._message_publishers[publisher_id]

    def _unknown_publisher(self, publisher_id: int) -> ApiError:
        """The 404 for a publisher id (call with the lock held)."""
        ids = ', '.join(map(str, self._message_publishers)) or 'none'
        return ApiError(404, f'no publisher {publisher_id} (publishers: {ids})')

    def _start_timer(self, entry: MessagePublisher) -> None:
        def publish() -> None:
            # Under the lock: a request thread may be removing this publisher right now.
            with self._state_lock:
                if self._message_publishers.get(entry.id) is not entry:
                    return
                if entry.stamps:
                    now = self.get_clock().now().to_msg()
                    for refresh in entry.stamps:
                        refresh(now)
                entry.publisher.publish(entry.message)
                entry.published += 1

        entry.timer = self.create_timer(1.0 / entry.rate, publish, autostart=entry.enabled)

    # ---- Service Caller ------------------------------------------------------------------------

    def call_service(self, body: dict[str, Any]) -> dict[str, Any]:
        """Call a service of the graph with the page's request: the response and how long it took (s).

        ApiError for an unknown service or type, a bad request, or no answer within the timeout.
        """
        check_keys(body, CALL_KEYS, required=('service',))
        service = api_input.name(body['service'], 'service')
        timeout = api_input.timeout(body.get('timeout', DEFAULT_CALL_TIMEOUT))
        values = api_input.fields(body.get('request'), 'request')
        given_type = api_input.optional_text(body.get('type'), 'type')
        known = api_input.known_name(service, self.service_types(), 'service')
        service_class = _message_type(given_type or api_input.single_type(service, known, 'service'), 'srv')
        if type_name_of(service_class) not in known:
            raise ApiError(400, f"service '{service}' has type {', '.join(known)}, "
                                f'not {type_name_of(service_class)}')
        request, _ = _filled(service_class.Request(), values)
        started = time.monotonic()
        response = self._call(service, service_class, request, timeout)
        return {'service': service, 'type': type_name_of(service_class),
                'response': message_fields(response), 'seconds': round(time.monotonic() - started, 3)}

    def _call(self, service: str, service_class: Any, request: Any, timeout: float) -> Any:
        with self._state_lock:
            client = self._service_clients.get((service, service_class))
            if client is None:
                try:
                    client = self.create_client(service_class, service)
                except InvalidServiceNameException as error:
                    raise ApiError(400, f"invalid service name '{service}': "
                                        f'{str(error).splitlines()[0]}') from None
                self._service_clients[(service, service_class)] = client
        deadline = time.monotonic() + timeout
        if not client.wait_for_service(timeout_sec=timeout):
            raise ApiError(504, f'service {service} did not become available within {timeout:g} s')
        answered = threading.Event()
        future = client.call_async(request)
        future.add_done_callback(lambda _: answered.set())
        if not answered.wait(max(0.0, deadline - time.monotonic())):
            client.remove_pending_request(future)
            raise ApiError(504, f'no response from {service} within {timeout:g} s')
        if future.exception() is not None:
            raise ApiError(502, f'the call of {service} failed: {future.exception()!r}')
        return future.result()

    # ---- Image View ----------------------------------------------------------------------------

    def image_topic_types(self) -> dict[str, list[str]]:
        """The topics Image View can show (a sensor_msgs Image or CompressedImage type), with their types."""
        return {name: types for name, types in self.topic_types().items()
                if any(t in IMAGE_TYPES for t in types)}

    def watch_images(self, watcher: Subscription) -> None:
        """Push every frame of an image topic to a page ({"channel": "image", "topic": ...})."""
        check_keys(watcher.params, IMAGE_KEYS, required=IMAGE_KEYS)
        feed = self._image_feed(watcher.params['topic'])
        with self._state_lock:
            feed.watchers.add(watcher)
            latest, error = feed.latest, feed.error
        if latest is not None:
            watcher.send_binary(*latest)
        elif error is not None:
            watcher.error(error)

    def stop_watching_images(self, watcher: Subscription) -> None:
        """The page unsubscribed from Image View or left."""
        self._drop_watcher(self._image_feeds, watcher)

    def _drop_watcher(self, feeds: dict[str, Any], watcher: Subscription) -> None:
        """A page left topics' feeds (ImageFeed, InspectedTopic); the last one out drops a subscription."""
        with self._state_lock:
            for topic, feed in list(feeds.items()):
                feed.watchers.discard(watcher)
                if not feed.watchers:
                    self.destroy_subscription(feed.subscription)
                    del feeds[topic]

    def _image_feed(self, wanted: Any) -> ImageFeed:
        topic = api_input.name(wanted, 'topic')
        with self._state_lock:
            if topic in self._image_feeds:
                return self._image_feeds[topic]
        types = api_input.known_name(topic, self.topic_types(), 'topic')
        image_type = next((t for t in types if t in IMAGE_TYPES), None)
        if image_type is None:
            raise ApiError(400, f"topic '{topic}' has type {', '.join(types)}; Image View shows "
                                f"{' and '.join(IMAGE_TYPES)}")
        with self._state_lock:
            if topic not in self._image_feeds:
                feed = ImageFeed(topic, image_type)
                # Best effort matches reliable and best-effort publishers (the camera is best effort).
                feed.subscription = self.create_subscription(
                    import_type(image_type, 'msg'), topic, lambda message: self._show_frame(feed, message),
                    qos_profile_sensor_data)
                self._image_feeds[topic] = feed
            return self._image_feeds[topic]

    def _show_frame(self, feed: ImageFeed, message: Any) -> None:
        """A frame arrived: push it to the watchers as the browser shows it (JPEG/PNG bytes)."""
        with self._state_lock:
            watchers = list(feed.watchers)
            feed.frames += 1
        try:
            if feed.type_name == 'sensor_msgs/msg/CompressedImage':
                content_type, data = compressed_for_browser(message.format, bytes(message.data))
            else:
                content_type, data = 'image/png', raw_to_png(
                    message.width, message.height, message.encoding, message.step,
                    bool(message.is_bigendian), bytes(message.data))
        except ImageError as error:
            self._tell_watchers(feed, f"cannot show the image on '{feed.topic}': {error}")
            return
        header = {'topic': feed.topic, 'frame': feed.frames, 'content_type': content_type}
        with self._state_lock:
            feed.latest, feed.error = (header, data), None
        for watcher in watchers:
            watcher.send_binary(header, data)

    def _tell_watchers(self, feed: ImageFeed, error: str) -> None:
        """An error line instead of frames, once (not at every frame)."""
        with self._state_lock:
            if error == feed.error:
                return
            feed.error = error
            watchers = list(feed.watchers)
        for watcher in watchers:
            watcher.error(error)

    # ---- topic inspector ----------------------------------------------------------------------

    def inspect_topic(self, watcher: Subscription) -> None:
        """Push a topic's last message, rate and endpoints to a page ({"channel": "topic", "topic": ...})."""
        check_keys(watcher.params, INSPECT_KEYS, required=INSPECT_KEYS)
        inspected = self._inspected_topic(watcher.params['topic'])
        with self._state_lock:
            inspected.watchers.add(watcher)
        watcher.send(self._inspection(inspected))

    def stop_inspecting(self, watcher: Subscription) -> None:
        """The page closed the inspector or left."""
        self._drop_watcher(self._inspected, watcher)

    def _inspected_topic(self, wanted: Any) -> InspectedTopic:
        topic = api_input.name(wanted, 'topic')
        with self._state_lock:
            if topic in self._inspected:
                return self._inspected[topic]
        type_name = api_input.known_name(topic, self.topic_types(), 'topic')[0]
        # The publishers' own policies where they all agree (a latched message comes too), as
        # `ros2 topic echo` subscribes; best effort takes reliable publishers' messages as well.
        reliability, durability = matching_policies(
            [endpoint_to_dict(info) for info in self.get_publishers_info_by_topic(topic)])
        qos = QoSProfile(depth=10, reliability=ReliabilityPolicy[reliability],
                         durability=DurabilityPolicy[durability])
        with self._state_lock:
            if topic not in self._inspected:
                inspected = InspectedTopic(topic, type_name)
                inspected.subscription = self.create_subscription(
                    import_type(type_name, 'msg'), topic,
                    lambda message: self._on_inspected(inspected, message), qos)
                self._inspected[topic] = inspected
            return self._inspected[topic]

    def _on_inspected(self, inspected: InspectedTopic, message: Any) -> None:
        with self._state_lock:
            inspected.count += 1
            inspected.latest = message
            inspected.rate.add(time.monotonic())
            inspected.fresh = True

    def _inspection(self, inspected: InspectedTopic) -> dict[str, Any]:
        """What the inspector shows of a topic now."""
        now = time.monotonic()
        with self._state_lock:
            latest, count, rate = inspected.latest, inspected.count, inspected.rate.rate(now)
            inspected.fresh, inspected.pushed = False, now
        endpoints = {side: [endpoint_summary(endpoint_to_dict(info)) for info in infos] for side, infos in (
            ('publishers', self.get_publishers_info_by_topic(inspected.topic)),
            ('subscribers', self.get_subscriptions_info_by_topic(inspected.topic)))}
        return {'topic': inspected.topic, 'type': inspected.type_name, 'count': count,
                'rate': None if rate is None else round(rate, 2),
                'message': None if latest is None else message_summary(latest), **endpoints}

    def _push_inspected_topics(self) -> None:
        now = time.monotonic()
        with self._state_lock:
            due = [(inspected, list(inspected.watchers)) for inspected in self._inspected.values()
                   if inspected.fresh or now - inspected.pushed >= INSPECTOR_REFRESH]
        for inspected, watchers in due:
            state = self._inspection(inspected)
            for watcher in watchers:
                watcher.send(state)

    def _report_silent_feeds(self) -> None:
        now = time.monotonic()
        with self._state_lock:
            silent = [feed for feed in self._image_feeds.values()
                      if feed.frames == 0 and feed.error is None and now - feed.started > FIRST_FRAME_TIMEOUT]
        for feed in silent:
            self._tell_watchers(feed, f"no image on '{feed.topic}' within {FIRST_FRAME_TIMEOUT:g} s")
