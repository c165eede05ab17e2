"""The 500 x 500 canvas: background colour, the pen-trail layer and the turtle sprites, free of ROS.

Layers as upstream paints them: a solid background, then a transparent "path" image holding the
trails, then every turtle in name order. The colour sensor reads the path layer only, so an
untouched pixel reads as white (the transparent fill is white with alpha 0).
"""

from __future__ import annotations

import io
import math
from collections.abc import Iterable
from dataclasses import dataclass
from functools import lru_cache
from typing import cast

from PIL import Image, ImageDraw

from turtlesim_py import world

DEFAULT_BACKGROUND = (69, 86, 255)
TRANSPARENT_WHITE = (255, 255, 255, 0)
SPRITE_PX = world.METER_PX
# One shell colour per Humble turtle image, so spawns still pick among 9 looks at random.
SHELL_COLORS = (
    (46, 139, 87), (34, 120, 60), (94, 160, 60), (60, 110, 140), (140, 110, 60),
    (120, 80, 150), (170, 70, 70), (40, 150, 150), (110, 130, 40),
)


@dataclass(frozen=True)
class SpriteView:
    """Where and how to draw one turtle: pixel centre, heading (rad) and look."""

    name: str
    x_px: float
    y_px: float
    theta: float
    sprite: int


class Canvas:
    """One simulator's drawing surface: the path layer of trails (size x size pixels) and the frames."""

    def __init__(self, size: int = world.CANVAS_PX) -> None:
        self.size = size
        self.path = Image.new('RGBA', (size, size), TRANSPARENT_WHITE)
        self._pen = ImageDraw.Draw(self.path)

    def clear(self) -> None:
        """Erase every trail: the path layer back to transparent."""
        self._pen.rectangle((0, 0, self.size, self.size), fill=TRANSPARENT_WHITE)

    def draw_line(self, start: tuple[float, float], end: tuple[float, float],
                  color: tuple[int, int, int], width: int) -> None:
        """An opaque pen segment in pixel coordinates; parts far off the canvas are cut away."""
        segment = clip_segment(start, end, -width - 1.0, self.size + width + 1.0)
        if segment is None:
            return
        (x0, y0), (x1, y1) = segment
        fill = (*color, 255)
        self._pen.line((x0, y0, x1, y1), fill=fill, width=width)
        if width > 2:
            # Stand-in for Qt's square caps: short segments then join without notches.
            half = width / 2.0
            for x, y in ((x0, y0), (x1, y1)):
                self._pen.rectangle((x - half + 0.5, y - half + 0.5, x + half - 0.5, y + half - 0.5),
                                    fill=fill)

    def sample(self, pixel: tuple[int, int]) -> tuple[int, int, int]:
        """RGB of the path layer at a pixel (what the colour sensor sees); alpha is ignored."""
        x, y = pixel
        if not (0 <= x < self.size and 0 <= y < self.size):
            return (0, 0, 0)
        r, g, b, _ = cast(tuple[int, int, int, int], self.path.getpixel((x, y)))  # an RGBA layer
        return (r, g, b)

    def render(self, background: tuple[int, int, int], turtles: Iterable[SpriteView]) -> Image.Image:
        """The visible image: background, trails, then turtles in lexicographic name order."""
        image = Image.new('RGBA', (self.size, self.size), (*background, 255))
        image.alpha_composite(self.path)
        for view in sorted(turtles, key=lambda v: v.name):
            sprite = rotated_sprite(view.sprite % len(SHELL_COLORS), _sprite_degrees(view.theta))
            left = round(view.x_px - sprite.width / 2.0)
            top = round(view.y_px - sprite.height / 2.0)
            image.paste(sprite, (left, top), sprite)  # paste, unlike alpha_composite, clips at edges
        return image.convert('RGB')


def encode_png(image: Image.Image) -> bytes:
    """The image as PNG bytes, as the simulator's CompressedImage frames carry it."""
    buffer = io.BytesIO()
    image.save(buffer, format='PNG')
    return buffer.getvalue()


def clip_segment(start: tuple[float, float], end: tuple[float, float], low: float,
                 high: float) -> tuple[tuple[float, float], tuple[float, float]] | None:
    """The part of a segment inside the square [low, high]^2 (Liang-Barsky), or None."""
    (x0, y0), (x1, y1) = start, end
    dx, dy = x1 - x0, y1 - y0
    t_enter, t_leave = 0.0, 1.0
    for p, q in ((-dx, x0 - low), (dx, high - x0), (-dy, y0 - low), (dy, high - y0)):
        if p == 0.0:
            if q < 0.0:
                return None
            continue
        t = q / p
        if p < 0.0:
            t_enter = max(t_enter, t)
        else:
            t_leave = min(t_leave, t)
        if t_enter > t_leave:
            return None
    return (x0 + t_enter * dx, y0 + t_enter * dy), (x0 + t_leave * dx, y0 + t_leave * dy)


def _sprite_degrees(theta: float) -> int:
    """Heading in whole degrees: finer turns would not show at 45 px, and it keeps the cache small."""
    return round(math.degrees(theta)) % 360


@lru_cache(maxsize=1024)
def rotated_sprite(look: int, degrees: int) -> Image.Image:
    """The sprite turned to face `degrees` counter-clockwise from +x (screen right)."""
    # The drawing faces up (90 degrees); PIL rotates counter-clockwise.
    return turtle_sprite(look).rotate(degrees - 90, resample=Image.Resampling.BICUBIC, expand=True)


@lru_cache(maxsize=len(SHELL_COLORS))
def turtle_sprite(look: int) -> Image.Image:
    """Our own turtle drawing, facing up, on a transparent 45 x 45 square."""
    s = SPRITE_PX
    image = Image.new('RGBA', (s, s), (0, 0, 0, 0))
    draw = ImageDraw.Draw(image)
    skin, outline = (150, 200, 110, 255), (30, 60, 30, 255)
    shell = (*SHELL_COLORS[look], 255)
    for cx, cy in ((12, 14), (33, 14), (12, 32), (33, 32)):  # legs
        draw.ellipse((cx - 5, cy - 4, cx + 5, cy + 4), fill=skin, outline=outline)
    draw.polygon(((20, 38), (25, 38), (22.5, 44)), fill=skin, outline=outline)  # tail
    draw.ellipse((16, 1, 29, 14), fill=skin, outline=outline)  # head
    draw.ellipse((19, 5, 21, 7), fill=outline)
    draw.ellipse((24, 5, 26, 7), fill=outline)
    draw.ellipse((10, 9, 35, 40), fill=shell, outline=outline, width=2)  # shell
    draw.line((22.5, 12, 22.5, 37), fill=outline, width=1)
    draw.line((13, 24.5, 32, 24.5), fill=outline, width=1)
    return image
