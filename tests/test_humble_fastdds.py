"""A ROS 2 Humble servo on real Fast DDS, its torque services called from our Jazzy side.

humble_fastdds_twin (src/common/owl_humble_fastdds, C++ on the venv's Fast DDS) is one Olive servo
as rmw_fastrtps on Humble is on the wire: graph message with 24-byte gids, endpoints without type
hashes, and the services setTorqueEnable/setTorqueDisable as request/reply topics whose replies
carry the request's sample identity. Fast DDS clients (our Jazzy `ros2 service call`, rclpy) take a
reply only with that identity: with the twin's --no-reply-identity the same call goes unanswered,
so the tests below can fail. Its node's parameter services answer `ros2 param`, and its --call is a
Humble client of a service of ours.
"""

import math
import re
import signal
import subprocess
import threading
import time
from pathlib import Path

import pytest
from owl_common.processes import RosSandbox, installed_executable
from owl_humble.launcher import ensure_discovery_bridge
from ros_harness import Probe, wait_until
from sensor_msgs.msg import Imu
from std_msgs.msg import Bool
from std_srvs.srv import Trigger
from web_harness import Rqt

ROOT = Path(__file__).resolve().parent.parent
PROFILE = ROOT / 'config' / 'fastdds.xml'
SERVO_NODE = '/olive_servo_humble_dcm_srv'
SERVICES = '/olive/servo/humble/'
# Tests wait 2 s for a new client's reply reader, as our own servers do (config/fastdds.xml): a
# Humble module's 0.1 s (Fast DDS's default max_blocking_time) is a race on a loaded machine.
TWIN_ARGS = ('--reply-wait', '2')
SUMMARY = r"discovery samples received: (\d+), malformed in Humble's layout: (\d+); replies sent: (\d+)"


def start_twin(sandbox, *args, node=SERVO_NODE):
    twin = sandbox.run('owl_humble_fastdds', 'humble_fastdds_twin', *TWIN_ARGS, *args, label='fastdds twin')
    twin.wait_for('ready: node ' + node, timeout=20)
    return twin


def stop_twin(twin):
    """Ctrl-C the twin; (graph messages received, malformed ones, replies sent) from its last line."""
    twin.send_signal(signal.SIGINT)
    assert twin.wait(10) == 0, twin.tail()
    return tuple(int(n) for n in twin.wait_for(SUMMARY)[0].groups())


def service_call(sandbox, service, timeout=20.0, env=None):
    """`ros2 service call` of a Trigger service: (its output, seconds the command took)."""
    started = time.monotonic()
    result = subprocess.run(['ros2', 'service', 'call', service, 'std_srvs/srv/Trigger'],
                            env={**sandbox.env, **(env or {})}, capture_output=True, text=True,
                            timeout=timeout, check=False)
    assert result.returncode == 0, result.stdout + result.stderr
    assert 'Traceback' not in result.stderr, result.stderr
    return result.stdout + result.stderr, time.monotonic() - started


def round_trip(probe, client):
    """One call of an rclpy client of the probe: (response, seconds from the call to the response)."""
    done = threading.Event()
    started = time.monotonic()
    future = client.call_async(Trigger.Request())
    future.add_done_callback(lambda _: done.set())
    assert done.wait(5.0), 'no response within 5 s'
    return future.result(), time.monotonic() - started


def ros2(sandbox, *args):
    """A `ros2` command's output (it must not fail; stdout, then stderr), and the seconds it took."""
    started = time.monotonic()
    result = subprocess.run(['ros2', *args], env=sandbox.env, capture_output=True, text=True, timeout=30,
                            check=False)
    assert result.returncode == 0, result.stdout + result.stderr
    assert 'Traceback' not in result.stderr, result.stderr
    return result.stdout + result.stderr, time.monotonic() - started


def node_list(sandbox):
    return set(ros2(sandbox, 'node', 'list')[0].split())


def test_our_service_and_param_calls_switch_the_humble_servos_torque_and_gains(page):
    with RosSandbox() as sandbox:
        twin = start_twin(sandbox)
        # In private mode nothing of ours starts the discovery bridge (no real module is there); it
        # names the twin's node to our tools from its Humble graph message, sent by real Fast DDS.
        ensure_discovery_bridge(sandbox.env, local_twin=True)

        out, enable_took = service_call(sandbox, SERVICES + 'setTorqueEnable')
        assert "Trigger_Response(success=True, message='torque enabled')" in out, out
        twin.wait_for(r"setTorqueEnable: torque enabled \(request #1 .* with the request's identity",
                      timeout=5)
        twin.wait_for('^humble_fastdds_twin: torque on$', timeout=5)

        # The appendix's clean-up, through rqt's Service Caller in a browser, as section 4.4 does it.
        rqt = Rqt(sandbox)
        disable = SERVICES + 'setTorqueDisable'
        page.goto(rqt.base + '#service-caller')
        page.wait_for_selector(f'#srv-names option[value="{disable}"]', state='attached', timeout=20_000)
        page.fill('#srv-name', disable)
        page.click('#srv-timeout')  # leaving the name's box chooses the service, as a student's click does
        page.wait_for_function('document.getElementById("srv-type").textContent === "std_srvs/srv/Trigger"')
        started = time.monotonic()
        page.click('#srv-call')
        page.wait_for_function('document.getElementById("srv-response").textContent'
                               '.includes("torque disabled")', timeout=10_000)
        disable_took = time.monotonic() - started
        assert page.inner_text('#srv-error') == ''
        response = page.inner_text('#srv-response')
        assert re.search(r'success\s+boolean\s+true', response), response
        page.screenshot_to('rqt_service_caller_humble_servo')
        twin.wait_for('^humble_fastdds_twin: torque off$', timeout=5)
        rqt.process.send_signal(signal.SIGINT)

        # The node's parameter services, as Humble's rclcpp answers: our ros2 param finds the node
        # through the bridge, then calls list/get/set_parameters.
        wait_until(lambda: SERVO_NODE in node_list(sandbox), 20, f'{SERVO_NODE} in ros2 node list')
        took = {}
        out, took['list'] = ros2(sandbox, 'param', 'list', SERVO_NODE)
        assert out.split() == ['kd', 'ki', 'kp', 'use_sim_time'], out
        out, took['get'] = ros2(sandbox, 'param', 'get', SERVO_NODE, 'kp')
        assert out.strip() == 'Double value is: 5.0', out
        out, took['set'] = ros2(sandbox, 'param', 'set', SERVO_NODE, 'kp', '2.5')
        assert out.strip() == 'Set parameter successful', out
        twin.wait_for('^humble_fastdds_twin: parameter kp = 2.5$', timeout=5)
        assert ros2(sandbox, 'param', 'get', SERVO_NODE, 'kp')[0].strip() == 'Double value is: 2.5'
        out, _ = ros2(sandbox, 'param', 'set', SERVO_NODE, 'kp', 'fast')
        assert ('Setting parameter failed: Wrong parameter type, parameter {kp} is of type {double}, '
                'setting it to {string} is not allowed.') in out, out

        # The round trip itself, once the client has found the service (rclpy, our Jazzy rmw).
        probe = Probe(sandbox.domain_id)
        try:
            rtts = {}
            for name, expected in (('setTorqueEnable', 'torque enabled'),
                                   ('setTorqueDisable', 'torque disabled')):
                client = probe.node.create_client(Trigger, SERVICES + name)
                assert client.wait_for_service(timeout_sec=10), name
                response, rtts[name] = round_trip(probe, client)
                assert (response.success, response.message) == (True, expected), response
        finally:
            probe.close()
        print(f'ros2 service call setTorqueEnable {enable_took:.2f} s (the whole command), rqt Service '
              f'Caller setTorqueDisable {disable_took:.2f} s (click to answer shown); round trip of an rclpy '
              'client: ' +
              ', '.join(f'{name} {seconds * 1000:.1f} ms' for name, seconds in rtts.items()) +
              '; requests arrived after (ms): ' +
              ', '.join(re.findall(r'arrived ([\d.-]+) ms after', twin.output)) +
              '; the twin replied after (ms): ' +
              ', '.join(re.findall(r'([\d.]+) ms after the request', twin.output)) +
              '; ros2 param ' + ', '.join(f'{verb} {seconds:.2f} s' for verb, seconds in took.items()))

        _, malformed, replies = stop_twin(twin)
        assert malformed == 0, twin.output
        assert replies == 9, twin.output


def test_the_courses_servo_programs_switch_a_humble_servos_torque_on_at_start_and_off_at_ctrl_c():
    """Section 4.4's control_servo and appendix 5.3's listing (pid_testing), both on the pan servo."""
    with RosSandbox() as sandbox:
        twin = start_twin(sandbox, '--namespace', 'pan', node='/olive_servo_pan_dcm_srv')
        for turn, program in enumerate(('control_servo', 'pid_testing'), start=1):
            node = sandbox.run('olive_servo', program)
            twin.wait_for(r'setTorqueEnable: torque enabled \(', timeout=20, count=turn)
            if program == 'control_servo':  # its goals once the torque is on (pid_testing's come after 3 s)
                node.wait_for('torque enabled: pan', timeout=10)
                twin.wait_for(r'goal [+-]\d\.\d{3} rad on /olive/servo/pan/goal/position$', timeout=10)
            node.send_signal(signal.SIGINT)
            assert node.wait(15) == 0, node.tail()
            twin.wait_for(r'setTorqueDisable: torque disabled \(', timeout=5, count=turn)
        _, malformed, replies = stop_twin(twin)
        assert malformed == 0, twin.output
        assert replies == 4, twin.output


def test_a_humble_imu_sends_its_tilt_answers_its_services_and_takes_its_led():
    with RosSandbox() as sandbox:
        twin = start_twin(sandbox, '--module', 'imu', node='/olive_imu_humble_dcm_srv')
        probe = Probe(sandbox.domain_id)
        try:
            readings = probe.collect(Imu, '/olive/imu/humble/imu')
            led = probe.node.create_publisher(Bool, '/olive/imu/humble/led', 10)
            out, _ = service_call(sandbox, '/olive/imu/humble/setZeroQuaternion')
            assert "Trigger_Response(success=True, message='orientation zeroed')" in out, out
            wait_until(lambda: readings, 10, 'an Imu from the twin')
            reading = readings[-1]
            assert reading.header.frame_id == 'humble_base_link'
            assert reading.orientation.y == pytest.approx(math.sin(0.15))
            assert reading.orientation.w == pytest.approx(math.cos(0.15))
            assert reading.linear_acceleration.z == pytest.approx(9.81 * math.cos(0.3))
            wait_until(lambda: led.get_subscription_count() > 0, 10, "the twin's led reader")
            led.publish(Bool(data=True))
            twin.wait_for('^humble_fastdds_twin: LED on$', timeout=5)
        finally:
            probe.close()
        assert stop_twin(twin)[1] == 0, twin.output


def test_a_humble_client_calls_a_service_of_ours_and_takes_its_answer():
    """The other way: the twin's --call is a client as rclcpp's on Humble, our rclpy node the server."""
    service = '/olive/servo/jazzy/setTorqueEnable'
    with RosSandbox() as sandbox:
        probe = Probe(sandbox.domain_id)
        try:
            calls = []

            def answer(request, response):
                calls.append(request)
                response.success, response.message = True, 'torque enabled (Jazzy)'
                return response

            probe.node.create_service(Trigger, service, answer)
            twin = start_twin(sandbox, '--call', service)
            took = twin.wait_for(rf"call {service}: success=true message='torque enabled \(Jazzy\)' "
                                 r'\(request #1, round trip ([\d.]+) ms\)', timeout=30)[0].group(1)
            print(f'a Humble client called {service} of ours: round trip {took} ms')
            assert len(calls) == 1
            assert stop_twin(twin)[1] == 0, twin.output
        finally:
            probe.close()


def test_without_the_requests_identity_on_the_reply_the_call_is_never_answered():
    with RosSandbox() as sandbox:
        twin = start_twin(sandbox, '--no-reply-identity')
        call = sandbox.command(['ros2', 'service', 'call', SERVICES + 'setTorqueEnable',
                                'std_srvs/srv/Trigger'], label='ros2 service call')
        twin.wait_for(r"setTorqueEnable: torque enabled \(request #1 .* WITHOUT the request's identity",
                      timeout=20)
        # The reply has gone out; a reply with the identity reaches the client within milliseconds.
        with pytest.raises(AssertionError, match='waited'):
            call.wait_for('^response:', timeout=1.5)
        assert call.running(), call.output
        call.stop(timeout=5)
        assert stop_twin(twin)[2] == 1, twin.output


def test_without_our_graph_partition_the_fastdds_twin_counts_the_messages_it_would_misread(tmp_path):
    text = PROFILE.read_text()
    stripped = re.sub(r'\s*<data_(writer|reader) profile_name="ros_discovery_info">.*?</data_\1>', '',
                      text, flags=re.S)
    assert stripped != text, 'the profile has no graph partition'
    unprotected = tmp_path / 'unprotected.xml'
    unprotected.write_text(stripped)
    with RosSandbox() as sandbox:
        twin = start_twin(sandbox)
        subprocess.run(['ros2', 'node', 'list', '--no-daemon'], check=True, capture_output=True, timeout=30,
                       env={**sandbox.env, 'FASTRTPS_DEFAULT_PROFILES_FILE': str(unprotected)})
        twin.wait_for('malformed discovery sample #1 ', timeout=20)
        received, malformed, _ = stop_twin(twin)
        assert malformed == received > 0, twin.output


@pytest.mark.parametrize(('args', 'error'), [
    (['--rate', 'fast'], "--rate 'fast' is not between 0 and 1000 messages per second"),
    (['--namespace', '9lives'], "--namespace '9lives' is not a ROS name"),
    (['--reply-wait'], 'argument --reply-wait: expected one value'),
    (['--module', 'camera'], "argument --module: invalid choice: 'camera' (choose from 'servo', 'imu')"),
    (['--led'], "unrecognized argument '--led'"),
    (['--call', 'setTorqueEnable'], "--call 'setTorqueEnable' is not an absolute service name"),
])
def test_a_bad_command_line_gets_one_error_line_and_exit_code_2(args, error):
    twin = installed_executable('owl_humble_fastdds', 'humble_fastdds_twin')
    result = subprocess.run([str(twin), *args], capture_output=True, text=True, timeout=10, check=False)
    assert result.returncode == 2, result
    assert result.stderr.splitlines()[-1].startswith(f'humble_fastdds_twin: error: {error}'), result.stderr
    assert result.stdout == '', result.stdout
