"""The head's answer to each gesture, and that it matches what the simulated camera says."""

import pytest
from olive_sim.scene_model import GESTURES as CAMERA_GESTURES
from olive_vision.gestures import GESTURES, MOTIONS, STEP, MotionPlayer, words


def test_every_gesture_the_camera_says_has_an_answer_and_the_same_words():
    assert {g.label: g.words.replace('_', ' ') for g in CAMERA_GESTURES} == {
        label: text.replace(' / ', ' ').replace(',', '') for label, (text, _) in GESTURES.items()}
    assert all(motion in MOTIONS for _, motion in GESTURES.values())
    assert words('2') == 'both hands up'
    assert words('none') == 'none'


def test_a_motion_plays_each_goal_for_a_step_then_ends():
    nod = MotionPlayer(MOTIONS['nod'], started=10.0)
    assert [nod.goal(10.0 + STEP * (i + 0.5)) for i in range(len(MOTIONS['nod']))] == MOTIONS['nod']
    assert nod.goal(10.0 + STEP * len(MOTIONS['nod']) + 0.01) is None
    assert nod.goal(9.0) is None


@pytest.mark.parametrize('motion', sorted(MOTIONS))
def test_every_motion_ends_facing_the_person(motion):
    assert MOTIONS[motion][-1] == (0.0, 0.0)  # the person stays in sight for the next gesture
