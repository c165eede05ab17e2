"""Canvas layers, trails, colour sampling and rendering (no ROS)."""

from __future__ import annotations

import io

from PIL import Image
from turtlesim_py.canvas import (
    DEFAULT_BACKGROUND,
    Canvas,
    SpriteView,
    clip_segment,
    encode_png,
    rotated_sprite,
)

PEN = (0xB3, 0xB8, 0xFF)


def test_untouched_path_layer_reads_white_whatever_the_background():
    canvas = Canvas()
    assert canvas.sample((0, 0)) == (255, 255, 255)
    assert canvas.sample((499, 499)) == (255, 255, 255)
    assert canvas.render((1, 2, 3), []).getpixel((250, 250)) == (1, 2, 3)


def test_line_is_opaque_pen_colour_and_clear_erases_it():
    canvas = Canvas()
    canvas.draw_line((100.0, 200.0), (300.0, 200.0), PEN, 3)
    for x in (100, 200, 300):
        assert canvas.sample((x, 200)) == PEN
        assert canvas.sample((x, 201)) == PEN  # 3 px wide
    assert canvas.sample((200, 203)) == (255, 255, 255)
    image = canvas.render(DEFAULT_BACKGROUND, [])
    assert image.getpixel((200, 200)) == PEN
    assert image.getpixel((200, 210)) == DEFAULT_BACKGROUND
    canvas.clear()
    assert canvas.sample((200, 200)) == (255, 255, 255)
    assert canvas.render(DEFAULT_BACKGROUND, []).getpixel((200, 200)) == DEFAULT_BACKGROUND


def test_one_pixel_pen():
    canvas = Canvas()
    canvas.draw_line((10.0, 10.0), (10.0, 50.0), (9, 9, 9), 1)
    assert canvas.sample((10, 30)) == (9, 9, 9)
    assert canvas.sample((11, 30)) == (255, 255, 255)


def test_huge_coordinates_are_clipped_not_fatal():
    canvas = Canvas()
    canvas.draw_line((250.0, 250.0), (1e30, 250.0), PEN, 3)
    assert canvas.sample((499, 250)) == PEN
    canvas.draw_line((-1e30, -1e30), (-1e29, -1e29), PEN, 3)  # entirely outside: nothing


def test_clip_segment():
    assert clip_segment((0, 0), (10, 0), -1, 5) == ((0, 0), (5, 0))
    assert clip_segment((-10, -10), (-5, -5), 0, 5) is None
    assert clip_segment((1, 1), (2, 2), 0, 5) == ((1, 1), (2, 2))
    (x0, y0), (x1, y1) = clip_segment((-5, 2.5), (10, 2.5), 0, 5)
    assert (x0, y0, x1, y1) == (0, 2.5, 5, 2.5)


def test_turtles_are_drawn_over_trails_in_name_order():
    canvas = Canvas()
    canvas.draw_line((0.0, 250.0), (499.0, 250.0), PEN, 3)
    image = canvas.render(DEFAULT_BACKGROUND, [SpriteView('turtle1', 250, 250, 0.0, 0)])
    assert image.getpixel((250, 250)) not in (PEN, DEFAULT_BACKGROUND)  # the shell covers the trail
    assert image.getpixel((20, 250)) == PEN
    assert image.getpixel((250, 200)) == DEFAULT_BACKGROUND  # 50 px away: beyond the sprite
    # turtle2 sorts after turtle10 and is drawn on top of it.
    on_top = canvas.render(DEFAULT_BACKGROUND, [SpriteView('turtle2', 100, 100, 0.0, 1),
                                                SpriteView('turtle10', 100, 100, 0.0, 0)])
    alone = canvas.render(DEFAULT_BACKGROUND, [SpriteView('turtle2', 100, 100, 0.0, 1)])
    assert on_top.getpixel((100, 100)) == alone.getpixel((100, 100))


def test_sprite_faces_along_theta():
    east = rotated_sprite(0, 0)
    north = rotated_sprite(0, 90)
    # The head is the only part beyond the shell on the facing side.
    assert east.getpixel((east.width - 4, east.height // 2))[3] > 0
    assert north.getpixel((north.width // 2, 3))[3] > 0
    assert north.getpixel((north.width - 4, north.height // 2))[3] == 0


def test_png_round_trip():
    canvas = Canvas()
    image = canvas.render((10, 20, 30), [])
    decoded = Image.open(io.BytesIO(encode_png(image)))
    assert decoded.size == (500, 500)
    assert decoded.convert('RGB').getpixel((5, 5)) == (10, 20, 30)
