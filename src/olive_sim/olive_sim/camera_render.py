"""What the camera on the pan/tilt head sees: a procedural 360 degree scene, rendered with numpy.

The scene is an equirectangular panorama: column = azimuth (0 straight ahead at pan 0, growing to
the left, i.e. counter-clockwise seen from above), row = elevation (+90 deg at the top). A pixel's
viewing ray depends on tilt only up to a rotation about the vertical, and pan just adds to the
azimuth, so the renderer keeps a per-pixel lookup for the current tilt and shifts it by pan.
"""

from __future__ import annotations

import io
import math

import numpy as np
from PIL import Image, ImageDraw, ImageFont

PANORAMA_WIDTH = 3600   # 0.1 deg per column
PANORAMA_HEIGHT = 1800  # 0.1 deg per row
TILT_STEP = 0.001       # rad: the lookup is rebuilt when tilt moves more than this

# (azimuth deg, colour, label): colours differ in hue so a test can find each one.
LANDMARKS = (
    (0.0, (220, 30, 30), 'A'),      # red tower, straight ahead at pan 0
    (90.0, (30, 170, 40), 'B'),     # green, to the left
    (180.0, (40, 60, 220), 'C'),    # blue, behind
    (270.0, (230, 210, 30), 'D'),   # yellow, to the right
    (45.0, (200, 40, 200), 'E'),    # magenta
    (135.0, (30, 200, 200), 'F'),   # cyan
    (225.0, (240, 140, 20), 'G'),   # orange
    (315.0, (245, 245, 245), 'H'),  # white
)
LANDMARK_WIDTH = 6.0      # deg of azimuth
LANDMARK_BOTTOM = -8.0    # deg of elevation
LANDMARK_TOP = 20.0


def focal_length(width: int, horizontal_fov: float) -> float:
    """Focal length in pixels of a pinhole camera `width` pixels wide seeing horizontal_fov rad."""
    return (width / 2) / math.tan(horizontal_fov / 2)


def _font(size: int) -> ImageFont.ImageFont:
    try:
        return ImageFont.load_default(size=size)
    except TypeError:  # Pillow without FreeType: the fixed bitmap font
        return ImageFont.load_default()


def build_panorama() -> np.ndarray:
    """The scene as an RGB array PANORAMA_HEIGHT x PANORAMA_WIDTH."""
    h, w = PANORAMA_HEIGHT, PANORAMA_WIDTH
    elevation = np.linspace(90.0, -90.0, h, dtype=np.float32)[:, None]
    sky = np.clip(elevation / 90.0, 0, 1)
    ground = np.clip(-elevation / 90.0, 0, 1)
    image = np.zeros((h, w, 3), dtype=np.float32)
    above = elevation >= 0
    for channel, (high, low) in enumerate(((90, 200), (140, 220), (220, 245))):
        image[..., channel] = np.where(above, low + (high - low) * sky, 0)
    for channel, (near, far) in enumerate(((70, 110), (95, 130), (55, 80))):
        image[..., channel] += np.where(above, 0, far + (near - far) * ground)
    panorama = Image.fromarray(image.astype(np.uint8))
    draw = ImageDraw.Draw(panorama)
    column = w / 360.0
    row = h / 180.0
    horizon = h // 2
    for degrees in range(0, 360, 15):  # ground grid: azimuth lines
        x = round(degrees * column)
        draw.line([(x, horizon), (x, h)], fill=(50, 70, 40), width=2)
    for degrees in range(5, 90, 10):   # and elevation rings
        y = round(horizon + degrees * row)
        draw.line([(0, y), (w, y)], fill=(50, 70, 40), width=2)
    draw.line([(0, horizon), (w, horizon)], fill=(40, 40, 40), width=3)
    font = _font(60)
    for azimuth, colour, label in LANDMARKS:
        left = round((azimuth - LANDMARK_WIDTH / 2) * column)
        right = round((azimuth + LANDMARK_WIDTH / 2) * column)
        top = round(horizon - LANDMARK_TOP * row)
        bottom = round(horizon - LANDMARK_BOTTOM * row)
        for offset in (0, w):  # a landmark at azimuth 0 straddles the seam
            draw.rectangle([left + offset, top, right + offset, bottom], fill=colour)
            draw.text(((left + right) / 2 + offset, top - 40), label, fill=(20, 20, 20),
                      font=font, anchor='mm')
    return np.asarray(panorama)


class CameraRenderer:
    """Renders width x height views of the panorama for a pan and tilt (rad) and encodes JPEG."""

    def __init__(self, width: int = 640, height: int = 480, horizontal_fov: float = math.radians(48.7),
                 panorama: np.ndarray | None = None) -> None:
        if width < 16 or height < 16:
            raise ValueError(f'image size {width}x{height} is too small (at least 16x16)')
        if not 0.05 < horizontal_fov < math.radians(170):
            raise ValueError(f'horizontal field of view {math.degrees(horizontal_fov):.1f} deg '
                             'is outside (3, 170) deg')
        self.width, self.height = width, height
        self.fx = self.fy = focal_length(width, horizontal_fov)
        self.cx, self.cy = (width - 1) / 2, (height - 1) / 2
        pano = build_panorama() if panorama is None else panorama
        # Two copies side by side: a shifted column index never needs a modulo.
        self._pixels = np.concatenate([pano, pano], axis=1).reshape(-1, 3)
        self._tilt: float | None = None
        self._base_index = np.empty(0)
        self._rays: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
        self._font = _font(16)

    def _rebuild(self, tilt: float) -> None:
        if self._rays is None:
            u = (np.arange(self.width, dtype=np.float32) - self.cx) / self.fx
            v = (np.arange(self.height, dtype=np.float32) - self.cy) / self.fy
            right, down = np.meshgrid(u, v)
            # Body frame x forward, y left, z up; a rotation keeps each ray's length.
            self._rays = (-right, -down, 1.0 / np.sqrt(1.0 + right * right + down * down))
        left, up, inverse_length = self._rays
        c, s = np.float32(math.cos(tilt)), np.float32(math.sin(tilt))
        x = c + s * up       # pitch the ray down by tilt about y
        z = c * up - s
        azimuth = np.arctan2(left, x)
        elevation = np.arcsin(np.clip(z * inverse_length, -1.0, 1.0))
        columns = np.rint(azimuth * np.float32(PANORAMA_WIDTH / (2 * math.pi))).astype(np.int32)
        columns %= PANORAMA_WIDTH
        rows = np.rint((np.float32(math.pi / 2) - elevation) * np.float32(PANORAMA_HEIGHT / math.pi))
        rows = np.clip(rows, 0, PANORAMA_HEIGHT - 1).astype(np.int32)
        self._base_index = rows * (2 * PANORAMA_WIDTH) + columns
        self._tilt = tilt

    def render(self, pan: float, tilt: float) -> np.ndarray:
        """RGB array height x width x 3 of the view at pan, tilt."""
        if self._tilt is None or abs(tilt - self._tilt) > TILT_STEP:
            self._rebuild(tilt)
        shift = round(pan * PANORAMA_WIDTH / (2 * math.pi)) % PANORAMA_WIDTH
        return self._pixels[self._base_index + shift]

    def jpeg(self, pan: float, tilt: float, caption: str, quality: int = 80) -> bytes:
        """The view with `caption` (frame counter and time) in the top-left corner, as JPEG."""
        image = Image.fromarray(self.render(pan, tilt))
        draw = ImageDraw.Draw(image)
        box = draw.textbbox((6, 4), caption, font=self._font)
        draw.rectangle([box[0] - 3, box[1] - 2, box[2] + 3, box[3] + 2], fill=(0, 0, 0))
        draw.text((6, 4), caption, fill=(255, 255, 255), font=self._font)
        buffer = io.BytesIO()
        image.save(buffer, format='JPEG', quality=quality)
        return buffer.getvalue()


def find_colour(rgb: np.ndarray, colour: tuple[int, int, int],
                tolerance: int = 60) -> tuple[float, float] | None:
    """Centroid (x, y) in pixels of the pixels within `tolerance` of `colour`, or None."""
    distance = np.abs(rgb.astype(np.int16) - np.array(colour, dtype=np.int16)).max(axis=2)
    ys, xs = np.nonzero(distance < tolerance)
    if len(xs) < 20:
        return None
    return float(xs.mean()), float(ys.mean())
