"""Drawing the scene's ball and person into a camera frame, and the gesture app's skeleton.

Frames are packed RGBX, one uint32 per pixel (camera_render's layout); shapes are filled with
numpy over their bounding box, clipped to the frame.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
from olive_kit.description import BALL_COLOUR

from olive_sim.scene_model import BONES, KEYPOINTS

BALL_HIGHLIGHT = (245, 70, 75)  # BALL_COLOUR's lit top left, still red (saturation 0.71, value 0.96)
SHIRT, TROUSERS, SKIN = (40, 90, 170), (45, 45, 60), (225, 185, 150)
KEYPOINT_COLOUR, BONE_COLOUR = (0, 0, 255), (255, 255, 0)  # as the camera's gesture app draws them


def packed(colour: tuple[int, int, int]) -> np.uint32:
    """A colour as one packed RGBX pixel (the frames' layout)."""
    return np.array([*colour, 0], dtype=np.uint8).view(np.uint32)[0]


def _box(frame: np.ndarray, xs: Sequence[float], ys: Sequence[float], margin: float
         ) -> tuple[slice, slice, np.ndarray, np.ndarray] | None:
    """(rows, columns, row and column coordinates) of the frame around points plus margin; None if off it."""
    height, width = frame.shape
    x0, x1 = max(0, math.floor(min(xs) - margin)), min(width, math.ceil(max(xs) + margin) + 1)
    y0, y1 = max(0, math.floor(min(ys) - margin)), min(height, math.ceil(max(ys) + margin) + 1)
    if x0 >= x1 or y0 >= y1:
        return None
    rows, columns = np.ogrid[y0:y1, x0:x1]
    return slice(y0, y1), slice(x0, x1), rows.astype(np.float32), columns.astype(np.float32)


def fill_disc(frame: np.ndarray, centre: tuple[float, float], radius: float,
              colour: tuple[int, int, int]) -> None:
    """Fill the disc of radius px around centre (x, y) in a packed frame, clipped to the frame."""
    x, y = centre
    box = _box(frame, (x,), (y,), radius)
    if box is not None:
        rows, columns, ys, xs = box
        frame[rows, columns][(xs - x) ** 2 + (ys - y) ** 2 <= radius * radius] = packed(colour)


def fill_segment(frame: np.ndarray, start: tuple[float, float], end: tuple[float, float], width: float,
                 colour: tuple[int, int, int]) -> None:
    """Fill the pixels within width/2 px of the segment start-end: a thick line with round ends."""
    (ax, ay), (bx, by) = start, end
    half = width / 2
    box = _box(frame, (ax, bx), (ay, by), half)
    if box is None:
        return
    rows, columns, ys, xs = box
    dx, dy = bx - ax, by - ay
    length2 = dx * dx + dy * dy
    t = np.clip(((xs - ax) * dx + (ys - ay) * dy) / length2, 0.0, 1.0) if length2 else np.float32(0.0)
    frame[rows, columns][(xs - ax - t * dx) ** 2 + (ys - ay - t * dy) ** 2 <= half * half] = packed(colour)


@dataclass(frozen=True)
class SceneView:
    """What stands in front of the panorama in one frame, as directions (azimuth, elevation) in rad."""

    ball: tuple[float, float] | None = None
    person: Mapping[str, tuple[float, float]] | None = None


@dataclass(frozen=True)
class Placed:
    """A SceneView in one view's pixels: the ball (x, y, radius) and the person's keypoints in front."""

    ball: tuple[float, float, float] | None
    keypoints: Mapping[str, tuple[float, float]]
    person_scale: float  # px per metre at the person's distance

    @property
    def signature(self) -> tuple[object, ...]:
        """Equal for two placements that draw the same pixels."""
        ball = None if self.ball is None else tuple(round(value, 1) for value in self.ball)
        return ball, tuple((name, round(x, 1), round(y, 1)) for name, (x, y) in self.keypoints.items())

    def inside(self, width: int, height: int) -> bool:
        """Whether all 17 keypoints of the person are in an image of this size."""
        return len(self.keypoints) == len(KEYPOINTS) and all(
            0 <= x < width and 0 <= y < height for x, y in self.keypoints.values())



def draw_person(frame: np.ndarray, keypoints: Mapping[str, tuple[float, float]], scale: float) -> None:
    """A person in clothes over their keypoints (px), scale px per metre at their distance."""
    def bone(a: str, b: str, width: float, colour: tuple[int, int, int]) -> None:
        if a in keypoints and b in keypoints:
            fill_segment(frame, keypoints[a], keypoints[b], width * scale, colour)

    def middle(a: str, b: str) -> tuple[float, float] | None:
        if a in keypoints and b in keypoints:
            return ((keypoints[a][0] + keypoints[b][0]) / 2, (keypoints[a][1] + keypoints[b][1]) / 2)
        return None

    for side in ('left', 'right'):
        bone(f'{side}_hip', f'{side}_knee', 0.14, TROUSERS)
        bone(f'{side}_knee', f'{side}_ankle', 0.12, TROUSERS)
    shoulders, hips = middle('left_shoulder', 'right_shoulder'), middle('left_hip', 'right_hip')
    if shoulders is not None and hips is not None:
        fill_segment(frame, shoulders, hips, 0.36 * scale, SHIRT)
    head = middle('left_ear', 'right_ear')
    if head is not None and shoulders is not None:
        fill_segment(frame, shoulders, head, 0.09 * scale, SKIN)
    for side in ('left', 'right'):
        bone(f'{side}_shoulder', f'{side}_elbow', 0.10, SHIRT)
        bone(f'{side}_elbow', f'{side}_wrist', 0.08, SKIN)
    if head is not None:
        fill_disc(frame, head, 0.11 * scale, SKIN)


def draw_ball(frame: np.ndarray, x: float, y: float, radius: float) -> None:
    """The red ball of radius px at (x, y), lit from the top left."""
    fill_disc(frame, (x, y), radius, BALL_COLOUR)
    fill_disc(frame, (x - radius * 0.3, y - radius * 0.3), radius * 0.35, BALL_HIGHLIGHT)


def draw_skeleton(frame: np.ndarray, keypoints: Mapping[str, tuple[float, float]]) -> None:
    """The skeleton the camera's gesture app draws: yellow bones 3 px wide, blue keypoints."""
    for a, b in BONES:
        if a in keypoints and b in keypoints:
            fill_segment(frame, keypoints[a], keypoints[b], 3, BONE_COLOUR)
    for point in keypoints.values():
        fill_disc(frame, point, 2, KEYPOINT_COLOUR)
