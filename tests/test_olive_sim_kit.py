"""`ros2 launch olive_sim owl_kit.launch.py`: the whole Owl Kit as the course's chapter 4 sees it."""

import pytest
from olive_kit.description import OWL_KIT
from ros_harness import wait_until
from sensor_msgs.msg import JointState
from std_msgs.msg import Float32
from std_srvs.srv import Trigger


def first_answer(ros, argv):
    """A fresh `ros2` process's answer, complete the first time, as a student at the kit sees it.

    ros2cli waits until discovery of every local participant has settled.
    """
    process = ros.command(argv, label=argv[1])
    assert process.wait(30) == 0, process.output
    return process


@pytest.mark.whole_kit
def test_the_kit_launch_brings_up_four_modules_with_the_course_topics(ros):
    kit = ros.command(['ros2', 'launch', 'olive_sim', 'owl_kit.launch.py'], label='owl_kit')
    kit.wait_for(r'Owl Kit simulated modules:', timeout=20)
    kit.wait_for(r'^camera eye +olive_camera_eye_dcm_srv +/olive/camera/eye/image/camera_info', timeout=5)
    probe = ros.probe
    for module in OWL_KIT:
        probe.wait_for_node(module.node, timeout=30)
    expected = {topic: [type_name] for module in OWL_KIT for topic, type_name in module.topics().items()}
    wait_until(lambda: expected.items() <= dict(probe.node.get_topic_names_and_types()).items(), 20,
               'every module topic in the graph')
    # The course's chapter 4 commands against the kit.
    course_lines = {'/olive/camera/eye/image/compressed [sensor_msgs/msg/CompressedImage]',
                    '/olive/servo/pan/goal/position [std_msgs/msg/Float32]',
                    '/olive/imu/x1684267976913/imu [sensor_msgs/msg/Imu]'}
    listing = first_answer(ros, ['ros2', 'topic', 'list', '-t'])
    assert course_lines <= set(listing.lines), listing.output
    info = first_answer(ros, ['ros2', 'topic', 'info', '/olive/camera/eye/image/compressed', '-v'])
    assert '  Reliability: BEST_EFFORT' in info.lines, info.output
    assert '  Durability: VOLATILE' in info.lines, info.output
    params = first_answer(ros, ['ros2', 'param', 'list'])
    pan_params = params.lines[params.lines.index('/olive_servo_pan_dcm_srv:') + 1:]
    assert {'  kp', '  ki', '  kd'} <= set(pan_params), params.output
    enable = ros.command(['ros2', 'service', 'call', '/olive/servo/pan/setTorqueEnable',
                          'std_srvs/srv/Trigger'], label='service_call')
    assert enable.wait(30) == 0, enable.output
    assert "message='torque enabled'" in enable.output, enable.output
    joints = probe.collect(JointState, '/olive/servo/pan/joint')
    publish = ros.command(['ros2', 'topic', 'pub', '--once', '/olive/servo/pan/goal/position',
                           'std_msgs/msg/Float32', '{data: 1.0}'], label='topic_pub')
    assert publish.wait(30) == 0
    wait_until(lambda: joints and abs(joints[-1].position[0] - 1.0) < 0.01, 15, 'pan at 1.0 rad')
    # Tilt carries the camera: its parameters came through the launch file.
    assert probe.get_parameters('olive_servo_tilt_dcm_srv', 'load_mass', 'max_position') == [0.12, 0.9]
    response = probe.call(Trigger, '/olive/servo/tilt/setTorqueEnable', Trigger.Request())
    assert response.success
    goal = probe.node.create_publisher(Float32, '/olive/servo/tilt/goal/position', 10)
    wait_until(lambda: goal.get_subscription_count() > 0, 10, 'tilt goal subscriber')
    goal.publish(Float32(data=2.0))
    kit.wait_for(r'\[servo_sim-3\].*goal/position 2\.0000 rad is outside \[-1\.3000, 0\.9000\]: clamped')
    kit.send_signal()
    assert kit.wait(30) == 0
    assert 'Traceback' not in kit.output
    assert kit.output.count('process has finished cleanly') == 4, kit.tail(80)
