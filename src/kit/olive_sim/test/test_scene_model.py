"""The ball's path, the person's gestures and the pinhole projection the camera draws them with."""

import math

import numpy as np
import pytest
from olive_kit.description import BALL_COLOUR
from olive_sim.camera_render import NO_RED_LANDMARKS, CameraRenderer, build_panorama
from olive_sim.scene_draw import SceneView, fill_disc, fill_segment, packed
from olive_sim.scene_model import (
    BALL_BOB,
    BALL_ELEVATION_RANGE,
    BALL_START,
    GESTURES,
    KEYPOINTS,
    BallPath,
    Pinhole,
    gesture_named,
    person_directions,
    person_pose,
    wrap,
)
from owl_common.images import find_colour

PINHOLE = Pinhole(706.0, 706.0, 319.5, 239.5)


@pytest.mark.parametrize(('azimuth', 'elevation', 'pan', 'tilt'), [
    (0.0, 0.0, 0.0, 0.0), (0.3, -0.1, 0.1, 0.2), (-0.2, 0.15, -0.4, -0.3), (3.0, 0.0, -3.1, 0.5)])
def test_a_projected_direction_comes_back_from_its_pixel(azimuth, elevation, pan, tilt):
    u, v = PINHOLE.project(azimuth, elevation, pan, tilt)
    assert PINHOLE.direction(u, v, pan, tilt) == pytest.approx((azimuth, elevation), abs=1e-9)


def test_left_is_left_and_down_is_down_and_behind_is_nowhere():
    centre = PINHOLE.project(0.0, 0.0, 0.0, 0.0)
    assert centre == pytest.approx((319.5, 239.5))
    left_u, _ = PINHOLE.project(0.1, 0.0, 0.0, 0.0)
    assert left_u == pytest.approx(319.5 - 706 * math.tan(0.1))
    _, below_v = PINHOLE.project(0.0, -0.1, 0.0, 0.0)
    assert below_v > 239.5
    # Tilting the camera down (positive tilt) brings what is below into the middle.
    assert PINHOLE.project(0.0, -0.1, 0.0, 0.1) == pytest.approx(centre)
    assert PINHOLE.project(math.pi, 0.0, 0.0, 0.0) is None


def test_the_projection_agrees_with_the_rendered_panorama():
    renderer = CameraRenderer(640, 480, math.radians(48.66), panorama=build_panorama(NO_RED_LANDMARKS))
    for pan, tilt in ((0.0, 0.0), (0.3, 0.2), (0.05, -0.2)):
        image = renderer.render(pan, tilt, SceneView(ball=(0.2, -0.1)))
        found = find_colour(image, BALL_COLOUR)
        assert found == pytest.approx(renderer.pinhole.project(0.2, -0.1, pan, tilt), abs=1.5)


def test_the_ball_scene_has_nothing_red_but_the_ball():
    renderer = CameraRenderer(320, 240, math.radians(120), panorama=build_panorama(NO_RED_LANDMARKS))
    for pan in np.linspace(-math.pi, math.pi, 8, endpoint=False):
        assert find_colour(renderer.render(pan, 0.0), BALL_COLOUR) is None, pan


def test_a_still_ball_stays_and_a_moving_one_goes_round_bobbing_within_the_world():
    still = BallPath(*BALL_START, speed=0.0, start=10.0)
    assert still.at(10.0) == still.at(99.0) == pytest.approx(BALL_START)
    moving = BallPath(0.0, 0.0, speed=0.2, start=0.0)
    assert moving.at(5.0)[0] == pytest.approx(1.0)
    elevations = [moving.at(t)[1] for t in np.linspace(0, 40, 400)]
    assert max(elevations) == pytest.approx(BALL_BOB, abs=0.005)
    assert min(elevations) == pytest.approx(-BALL_BOB, abs=0.005)
    assert moving.at(100 * math.pi / 0.2)[0] == pytest.approx(0.0, abs=1e-9)  # 10 turns: round again
    low, high = BALL_ELEVATION_RANGE
    edge = BallPath(0.0, high, speed=1.0, start=0.0)
    assert all(low <= edge.at(t)[1] <= high for t in np.linspace(0, 10, 100))


def test_putting_the_ball_somewhere_or_changing_its_speed_goes_on_from_where_it_is():
    path = BallPath(0.0, 0.0, speed=0.2, start=0.0)
    here = path.at(3.0)
    slower = path.moved(3.0, speed=0.1)
    assert slower.at(3.0) == pytest.approx(here)
    assert slower.at(4.0)[0] == pytest.approx(here[0] + 0.1)
    put = path.moved(3.0, azimuth=-0.5)
    assert put.at(3.0) == pytest.approx((-0.5, here[1]))
    assert wrap(3.5) == pytest.approx(3.5 - 2 * math.pi)


def test_a_swinging_ball_goes_to_and_fro_about_where_it_was_put_and_keeps_its_swing_through_changes():
    path = BallPath(0.25, 0.0, speed=0.3, start=0.0, swing=1.0)
    azimuths = [path.at(t)[0] for t in np.linspace(0, 60, 1200)]
    assert max(azimuths) == pytest.approx(1.25, abs=0.005)
    assert min(azimuths) == pytest.approx(-0.75, abs=0.005)
    # it passes the middle at its speed, and is back there after half a period (pi * swing / speed)
    assert (path.at(0.01)[0] - path.at(0.0)[0]) / 0.01 == pytest.approx(0.3, rel=1e-3)
    assert path.at(math.pi / 0.3)[0] == pytest.approx(0.25, abs=1e-9)
    # a new speed keeps the middle and the place in the swing; a new place is the new middle
    here = path.at(4.0)
    faster = path.moved(4.0, speed=0.6)
    assert faster.at(4.0) == pytest.approx(here)
    assert max(faster.at(t)[0] for t in np.linspace(4, 30, 600)) == pytest.approx(1.25, abs=0.005)
    put = path.moved(4.0, azimuth=-0.5)
    assert put.at(4.0)[0] == pytest.approx(-0.5)
    assert max(put.at(t)[0] for t in np.linspace(4, 30, 600)) == pytest.approx(0.5, abs=0.005)
    # a swing set on a ball going round is about where it is; a swing of 0 sends it round again
    swinging = BallPath(0.0, 0.0, speed=0.2, start=0.0).moved(5.0, swing=0.5)
    assert swinging.at(5.0)[0] == pytest.approx(1.0)
    assert max(swinging.at(t)[0] for t in np.linspace(5, 40, 700)) == pytest.approx(1.5, abs=0.005)
    round_again = swinging.moved(6.0, swing=0.0)
    assert round_again.at(7.0)[0] == pytest.approx(round_again.at(6.0)[0] + 0.2)


def test_each_gesture_puts_the_arms_where_its_name_says():
    def wrist_above_shoulder(pose, side):
        return pose[f'{side}_wrist'][1] > pose[f'{side}_shoulder'][1]

    for gesture in GESTURES:
        pose = person_pose(gesture)
        assert tuple(pose) == KEYPOINTS
        for side, arm in (('left', gesture.left_arm), ('right', gesture.right_arm)):
            assert wrist_above_shoulder(pose, side) == (arm == 'up'), (gesture.name, side)
    # Facing the robot, the person's left hand is on the robot's right (negative y).
    pose = person_pose(gesture_named('left_down_right_side'))
    assert pose['right_wrist'][0] > 0.5
    assert pose['left_wrist'][0] < 0
    assert len({g.label for g in GESTURES}) == len({g.name for g in GESTURES}) == 7
    with pytest.raises(ValueError, match="unknown gesture 'wave': expected one of both_hands_down"):
        gesture_named('wave')


def test_the_whole_person_is_in_the_picture_at_rest_and_not_when_the_head_turns_away():
    renderer = CameraRenderer(640, 480, math.radians(48.66))
    for gesture in GESTURES:
        scene = SceneView(person=person_directions(gesture))
        assert renderer.place(scene, 0.0, 0.0).inside(640, 480), gesture.name
        assert not renderer.place(scene, 0.6, 0.0).inside(640, 480), gesture.name


def test_discs_and_thick_segments_fill_what_they_cover_and_stop_at_the_frame():
    frame = np.zeros((40, 60), dtype=np.uint32)
    fill_disc(frame, (10.0, 10.0), 3.0, (255, 0, 0))
    assert (frame == packed((255, 0, 0))).sum() == 29  # the lattice points within radius 3
    fill_segment(frame, (-100.0, 30.0), (200.0, 30.0), 3.0, (0, 255, 0))
    assert (frame[29:32] == packed((0, 255, 0))).all()
    assert (frame == packed((0, 255, 0))).sum() == 3 * 60
    fill_disc(frame, (500.0, 500.0), 5.0, (0, 0, 255))  # off the frame: nothing
    fill_segment(frame, (5.0, 5.0), (5.0, 5.0), 2.0, (0, 0, 255))  # a point: a disc
    assert (frame == packed((0, 0, 255))).sum() == 5
