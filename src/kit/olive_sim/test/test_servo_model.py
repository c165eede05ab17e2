"""The servo model and its firmware PID as pure fixed-step functions: no ROS, no wall clock."""

import math

import pytest
from olive_sim.servo_model import (
    PidGains,
    ServoParams,
    ServoSim,
    course_exercise,
    simulate_step,
    step_metrics,
)

# The course's section 4.4 exercise, step 0 -> 1.57 rad as the appendix 5.3 script commands.
P_ONLY = PidGains(kp=1.0)
FAST_P = PidGains(kp=5.0)       # "raise Kp until the servo reaches the desired speed"
WITH_I = PidGains(kp=5.0, ki=10.0)
WITH_D = PidGains(kp=5.0, ki=10.0, kd=1.0)  # the course's first Kd


def run(sim: ServoSim, seconds: float) -> None:
    for _ in range(round(seconds / sim.dt)):
        sim.step()


def test_p_only_leaves_a_visible_remaining_error():
    metrics = simulate_step(P_ONLY)
    assert metrics.steady_state_error > 0.03  # rad: friction holds the joint short of the goal


def test_larger_kp_is_faster_and_overshoots_more():
    slow, fast = simulate_step(P_ONLY), simulate_step(FAST_P)
    assert fast.rise_time < slow.rise_time * 0.85
    assert fast.overshoot > slow.overshoot + 0.05
    assert fast.steady_state_error < slow.steady_state_error


def test_raising_ki_from_the_courses_start_removes_the_remaining_error():
    # The course: "introduce Ki, starting with 0.01", raise it until no error remains.
    errors = {ki: simulate_step(PidGains(kp=5.0, ki=ki)).steady_state_error
              for ki in (0.01, 0.1, 1.0, 10.0)}
    assert errors[0.01] > 0.01
    assert errors[10.0] < 0.01
    assert simulate_step(FAST_P).steady_state_error > 0.01  # without Ki it stays


def test_kd_reduces_the_overshoot():
    without, with_d = simulate_step(WITH_I), simulate_step(WITH_D)
    assert with_d.overshoot < without.overshoot / 2
    assert simulate_step(PidGains(kp=5.0, ki=10.0, kd=0.3)).overshoot < 0.01  # raised further


def test_the_whole_exercise_on_one_servo_shows_the_four_observations():
    # As a student does it: one running servo, gains changed between the script's goal flips.
    (_, p_only), (_, fast), (_, with_i), (_, with_d) = course_exercise()
    assert p_only.steady_state_error > 0.03
    assert fast.rise_time < p_only.rise_time
    assert fast.overshoot > p_only.overshoot + 0.05
    assert with_i.steady_state_error < 0.01
    assert with_d.overshoot < with_i.overshoot / 2


def test_a_new_ki_acts_without_a_jump():
    sim = ServoSim(gains=PidGains(kp=5.0))
    sim.enable_torque(True)
    sim.goal_position = 0.05  # inside friction's dead band: P alone leaves the error
    run(sim, 1.0)
    sim.pid.gains.ki = 10.0
    sim.step()
    assert abs(sim.effort - 5.0 * (0.05 - sim.measured_position())) < 0.01


def test_step_response_is_deterministic():
    assert simulate_step(WITH_D) == simulate_step(WITH_D)


def test_step_metrics_of_a_known_curve():
    times = [i * 0.01 for i in range(301)]
    positions = [min(1.0, t) + (0.1 if 1.0 <= t < 1.5 else 0.0) for t in times]
    m = step_metrics(times, positions, 0.0, 1.0)
    assert m.rise_time == pytest.approx(0.8, abs=0.011)
    assert m.overshoot == pytest.approx(0.1)
    assert m.steady_state_error == pytest.approx(0.0, abs=1e-9)
    with pytest.raises(ValueError, match='no step'):
        step_metrics(times, positions, 1.0, 1.0)


def test_torque_off_ignores_the_goal_and_coasts():
    sim = ServoSim()
    sim.state.velocity = 2.0
    sim.goal_position = 1.0
    run(sim, 1.0)
    assert sim.state.torque == 0.0
    assert sim.state.velocity == 0.0  # friction stopped it
    assert 0.0 < sim.state.position < 1.0


def test_enabling_torque_holds_the_current_position():
    sim = ServoSim()
    sim.state.position = 0.5
    sim.goal_position = 1.3
    sim.enable_torque(True)
    run(sim, 1.0)
    assert sim.goal_position == pytest.approx(0.5)
    assert sim.state.position == pytest.approx(0.5, abs=0.01)


def test_speed_and_torque_limits():
    sim = ServoSim(ServoParams(coulomb_friction=0.0, viscous_friction=0.0))
    sim.set_mode('pwm')
    sim.enable_torque(True)
    sim.pwm = 1.0
    run(sim, 2.0)
    assert sim.state.velocity == pytest.approx(sim.params.no_load_speed, rel=0.01)
    limited = ServoSim(ServoParams(max_torque=0.5))
    limited.set_mode('pwm')
    limited.enable_torque(True)
    limited.pwm = 1.0
    limited.step()
    assert limited.state.torque == pytest.approx(0.5)


def test_velocity_mode_tracks_the_goal_velocity():
    sim = ServoSim()
    sim.set_mode('velocity')
    sim.enable_torque(True)
    sim.goal_velocity = -2.0
    run(sim, 2.0)
    assert sim.state.velocity == pytest.approx(-2.0, abs=0.1)


def test_pwm_mode_speed_grows_with_duty():
    speeds = []
    for duty in (0.3, 0.6):
        sim = ServoSim()
        sim.set_mode('pwm')
        sim.enable_torque(True)
        sim.pwm = duty
        run(sim, 1.5)
        speeds.append(sim.state.velocity)
    assert 0 < speeds[0] < speeds[1]


def test_gravity_pulls_the_tilt_load_down_and_the_pid_holds_it():
    heavy = ServoParams(load_mass=1.0, load_offset=0.05)  # 0.49 N*m > friction
    sim = ServoSim(heavy)
    run(sim, 0.5)
    assert sim.state.position > 0.05  # torque off: the load sags (positive tilt is down)
    held = ServoSim(heavy, gains=PidGains(5.0, 10.0, 0.3))
    held.enable_torque(True)
    run(held, 2.0)
    assert abs(held.state.position) < 0.01


def test_temperature_rises_with_effort():
    # Pushing against a stop (friction larger than the motor can overcome) heats the motor.
    idle, working = ServoSim(), ServoSim(ServoParams(coulomb_friction=2.0))
    working.set_mode('pwm')
    working.enable_torque(True)
    working.pwm = 1.0
    run(idle, 5.0)
    run(working, 5.0)
    assert idle.state.temperature == pytest.approx(25.0)
    assert working.state.temperature > 25.5


def test_goals_are_clamped_to_the_range():
    sim = ServoSim(ServoParams(min_position=-1.0, max_position=0.5))
    assert sim.clamp_goal(2.0) == 0.5
    assert sim.clamp_goal(-3.0) == -1.0


@pytest.mark.parametrize(('kwargs', 'message'), [
    ({'inertia': 0.0}, 'inertia must be a positive'),
    ({'coulomb_friction': -1.0}, 'coulomb_friction must be zero or positive'),
    ({'min_position': 1.0, 'max_position': 0.0}, 'must be below'),
    ({'stall_torque': math.nan}, 'stall_torque'),
])
def test_impossible_constants_are_refused(kwargs, message):
    with pytest.raises(ValueError, match=message):
        ServoSim(ServoParams(**kwargs))


def test_rates_and_modes_are_checked():
    with pytest.raises(ValueError, match='at least 1000'):
        ServoSim(physics_rate=500.0)
    with pytest.raises(ValueError, match='pid_rate'):
        ServoSim(pid_rate=5000.0)
    with pytest.raises(ValueError, match="unknown control mode 'torque'"):
        ServoSim().set_mode('torque')


@pytest.mark.parametrize('mode', ['position', 'velocity', 'pwm'])
def test_a_batch_of_steps_is_exactly_the_single_steps(mode):
    def servo():
        sim = ServoSim(ServoParams(load_mass=0.12), gains=PidGains(5.0, 10.0, 0.3))
        sim.set_mode(mode)
        sim.enable_torque(True)
        sim.goal_position, sim.goal_velocity, sim.pwm = 1.2, 2.0, 0.6
        return sim

    single, batched = servo(), servo()
    for _ in range(1500):
        single.step()
    for count in (7, 13, 0, 480, 1000):  # batches that start and end between controller ticks
        batched.advance(min(count, 1500 - batched.steps))
    assert batched.steps == single.steps == 1500
    assert batched.time == single.time
    assert batched.state == single.state
    assert batched.effort == single.effort
