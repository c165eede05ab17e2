import threading

import pytest
import rclpy
from owl_common.polled_subscription import PolledSubscription
from rclpy.exceptions import InvalidTopicNameException
from rclpy.experimental import EventsExecutor
from std_msgs.msg import Float32

TOPIC = 'polled_subscription_test'


@pytest.fixture
def node():
    context = rclpy.Context()
    rclpy.init(context=context)
    node = rclpy.create_node('polled_subscription_test', context=context)
    yield node
    node.destroy_node()
    rclpy.shutdown(context=context)


def published_and_matched(node, subscription_count=1):
    publisher = node.create_publisher(Float32, TOPIC, 10)
    matched = threading.Event()
    for _ in range(200):
        if publisher.get_subscription_count() >= subscription_count:
            matched.set()
            break
        matched.wait(0.01)
    assert matched.is_set(), 'the polled subscription never matched the publisher'
    return publisher


def test_an_executor_never_takes_its_messages_and_a_poll_hands_them_over_in_order_with_their_info(node):
    taken = []
    polled = PolledSubscription(node, Float32, TOPIC,
                                lambda message, info: taken.append((message.data, info)), 10, info=True)
    assert not list(node.subscriptions), 'the node lists the polled subscription: executors would take it'
    publisher = published_and_matched(node)
    executor = EventsExecutor(context=node.context)
    executor.add_node(node)
    for value in (1.0, 2.0, 3.0):
        publisher.publish(Float32(data=value))
    for _ in range(5):  # the executor runs what it knows of; a polled message is not among it
        executor.spin_once(timeout_sec=0.05)
    assert taken == []
    polled.poll()
    assert [value for value, _ in taken] == [1.0, 2.0, 3.0]
    assert all(info['source_timestamp'] > 0 for _, info in taken)
    executor.shutdown()
    polled.destroy()


def test_a_destroyed_polled_subscription_hands_over_nothing_more(node):
    taken = []
    polled = PolledSubscription(node, Float32, TOPIC, lambda message: taken.append(message.data), 10)
    publisher = published_and_matched(node)
    polled.destroy()
    publisher.publish(Float32(data=1.0))
    polled.poll()
    polled.destroy()  # twice is harmless
    assert taken == []


def test_a_bad_topic_name_is_refused_as_by_create_subscription(node):
    with pytest.raises(InvalidTopicNameException, match='not a topic'):
        PolledSubscription(node, Float32, 'not a topic', lambda message: None, 10)
