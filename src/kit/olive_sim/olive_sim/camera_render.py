"""What the camera on the pan/tilt head sees: a procedural 360 degree scene, rendered with numpy.

The scene is an equirectangular panorama: column = azimuth (0 straight ahead at pan 0, growing to
the left, i.e. counter-clockwise seen from above), row = elevation (+90 deg at the top). A pixel's
viewing ray depends on tilt only up to a rotation about the vertical, and pan just adds to the
azimuth, so the renderer keeps a per-pixel lookup for the current tilt and shifts it by pan.
"""

from __future__ import annotations

import hashlib
import io
import math
import os
import re
import tempfile
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
import PIL
from PIL import Image, ImageDraw, ImageFont

from olive_sim.scene_draw import Placed, SceneView, draw_ball, draw_person, draw_skeleton
from olive_sim.scene_model import BALL_RADIUS, PERSON_DISTANCE, Pinhole

PANORAMA_WIDTH = 3600   # 0.1 deg per column
PANORAMA_HEIGHT = 1800  # 0.1 deg per row
TILT_STEP = 0.001       # rad: the lookup is rebuilt when tilt moves more than this
CAPTION_AT = (6, 4)     # px: top-left corner of the caption text
CAPTION_MARGIN = (3, 2)  # px of black box around it
BLOCK_ROWS = 16         # px: height of a JPEG block row with 4:2:0 chroma subsampling
_RESTART = re.compile(rb'\xff[\xd0-\xd7]')  # RST0..RST7; a 0xFF in coded data is followed by 0x00
# ImageFont.load_default gives a FreeType font, or Pillow's bitmap font where FreeType is missing.
Font = ImageFont.FreeTypeFont | ImageFont.ImageFont

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
# The ball's and the person's scenes: no red but the ball's (the tower straight ahead turns slate grey).
NO_RED_LANDMARKS = ((0.0, (110, 115, 125), 'A'), *LANDMARKS[1:])
LANDMARK_WIDTH = 6.0      # deg of azimuth
LANDMARK_BOTTOM = -8.0    # deg of elevation
LANDMARK_TOP = 20.0


def focal_length(width: int, horizontal_fov: float) -> float:
    """Focal length in pixels of a pinhole camera `width` pixels wide seeing horizontal_fov rad."""
    return (width / 2) / math.tan(horizontal_fov / 2)


def _font(size: int) -> Font:
    try:
        return ImageFont.load_default(size=size)
    except TypeError:  # Pillow without FreeType: the fixed bitmap font
        return ImageFont.load_default()


def build_panorama(landmarks: Sequence[tuple[float, tuple[int, int, int], str]] = LANDMARKS) -> np.ndarray:
    """The scene, with these landmarks, as an RGB array PANORAMA_HEIGHT x PANORAMA_WIDTH."""
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
    for azimuth, colour, label in landmarks:
        left = round((azimuth - LANDMARK_WIDTH / 2) * column)
        right = round((azimuth + LANDMARK_WIDTH / 2) * column)
        top = round(horizon - LANDMARK_TOP * row)
        bottom = round(horizon - LANDMARK_BOTTOM * row)
        for offset in (0, w):  # a landmark at azimuth 0 straddles the seam
            draw.rectangle([left + offset, top, right + offset, bottom], fill=colour)
            draw.text(((left + right) / 2 + offset, top - 40), label, fill=(20, 20, 20),
                      font=font, anchor='mm')
    return np.asarray(panorama)


def packed_panorama(panorama: np.ndarray) -> np.ndarray:
    """An RGB panorama as the renderer reads it: RGBX pixels as flat uint32, two copies side by side.

    With two copies a column shifted by pan never needs a modulo.
    """
    packed = np.zeros((PANORAMA_HEIGHT, 2 * PANORAMA_WIDTH, 4), dtype=np.uint8)
    packed[:, :PANORAMA_WIDTH, :3] = panorama
    packed[:, PANORAMA_WIDTH:, :3] = panorama
    return packed.view(np.uint32).reshape(-1)


def cache_folder() -> Path:
    """Where the simulated kit keeps what it computes once per machine: $XDG_CACHE_HOME/owl-kit-lab."""
    return Path(os.environ.get('XDG_CACHE_HOME') or Path.home() / '.cache') / 'owl-kit-lab'


# s: a cached panorama no camera has used for this long goes when another one is written (a file
# per version of this module: a developer's edits would otherwise pile up 52 MB each).
UNUSED_PANORAMA_KEPT = 7 * 24 * 3600.0


def scene_pixels(landmarks: Sequence[tuple[float, tuple[int, int, int], str]] = LANDMARKS,
                 folder: Path | None = None) -> np.ndarray:
    """packed_panorama(build_panorama(landmarks)), read from a file that every camera shares.

    Building it took 0.3 s of CPU at each camera's start and 70 MB of memory per camera; the file,
    mapped read-only, is built once (its name changes with this module, the landmarks and Pillow's
    font) and its pages are shared. Where the file cannot be read or written it is built in memory.
    """
    folder = folder or cache_folder()
    key = hashlib.sha256(Path(__file__).read_bytes() + repr((landmarks, PIL.__version__)).encode())
    path = folder / f'panorama-{key.hexdigest()[:16]}.npy'
    size = PANORAMA_HEIGHT * 2 * PANORAMA_WIDTH
    try:
        pixels = np.load(path, mmap_mode='r')
        if pixels.dtype == np.uint32 and pixels.shape == (size,):
            os.utime(path)  # in use: see UNUSED_PANORAMA_KEPT
            return pixels
    except (OSError, ValueError):
        pass
    pixels = packed_panorama(build_panorama(landmarks))
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.NamedTemporaryFile(dir=folder, suffix='.npy', delete=False) as written:
            np.save(written, pixels)
        os.replace(written.name, path)  # whole or not at all, whichever camera writes it first
        unused_since = path.stat().st_mtime - UNUSED_PANORAMA_KEPT
        for old in folder.glob('panorama-*.npy'):
            if old.stat().st_mtime < unused_since:
                old.unlink(missing_ok=True)
    except OSError:
        pass
    return pixels


class CaptionWriter:
    """Draws one line of white text on a black box into a packed RGBX frame, glyph by glyph.

    Each character is rasterised once with the font and then copied with numpy: drawing the
    caption through ImageDraw on every frame cost about a third of the time of a whole frame.
    """

    def __init__(self, font: Font) -> None:
        self._font = font
        if isinstance(font, ImageFont.FreeTypeFont):
            ascent, descent = font.getmetrics()
            self.line_height = ascent + descent
        else:  # Pillow's bitmap font (Pillow without FreeType) has no metrics: its tallest box
            self.line_height = int(font.getbbox('Ày')[3])
        self._glyphs: dict[str, tuple[np.ndarray, int]] = {}

    def _glyph(self, character: str) -> tuple[np.ndarray, int]:
        """(coverage as packed grey pixels line_height high, advance in px) of one character."""
        if character not in self._glyphs:
            advance = round(self._font.getlength(character))
            _, _, right, _ = self._font.getbbox(character)
            image = Image.new('L', (max(1, advance, math.ceil(right)), self.line_height), 0)
            ImageDraw.Draw(image).text((0, 0), character, fill=255, font=self._font)
            coverage = np.asarray(image)
            # The same byte in R, G, B and X: grey, whatever the byte order of uint32.
            packed = np.repeat(coverage[..., None], 4, axis=2).view(np.uint32)[..., 0]
            self._glyphs[character] = (np.ascontiguousarray(packed), advance)
        return self._glyphs[character]

    def draw(self, frame: np.ndarray, text: str, x: int, y: int,
             margin: tuple[int, int] = CAPTION_MARGIN) -> None:
        """Draw text with its top-left corner at (x, y) on a black box `margin` px larger, in place."""
        glyphs = [self._glyph(character) for character in text]
        width = sum(advance for _, advance in glyphs)
        height, frame_width = frame.shape
        mx, my = margin
        frame[max(0, y - my):max(0, y + self.line_height + my),
              max(0, x - mx):max(0, x + width + mx)] = 0
        for coverage, advance in glyphs:
            right = min(frame_width, x + coverage.shape[1])
            bottom = min(height, y + self.line_height)
            if x >= frame_width or y >= height:
                break
            target = frame[y:bottom, x:right]
            # Neighbouring glyphs may overlap by a pixel: keep the brighter coverage.
            np.maximum(target, coverage[:bottom - y, :right - x], out=target)
            x += advance


def encode_jpeg(frame: np.ndarray, quality: int) -> bytes:
    """A packed RGBX frame as baseline JPEG with 4:2:0 chroma and a restart marker after each block row.

    The markers make every block row a separately coded piece of the file (see SplicedJpeg).
    """
    height, width = frame.shape
    image = Image.frombuffer('RGB', (width, height), frame, 'raw', 'RGBX', 0, 1)
    buffer = io.BytesIO()
    image.save(buffer, format='JPEG', quality=quality, subsampling='4:2:0', restart_marker_rows=1)
    return buffer.getvalue()


def split_jpeg(data: bytes) -> tuple[bytes, list[bytes]]:
    """(everything up to the coded data, the coded data of each block row) of encode_jpeg's output."""
    start = data.index(b'\xff\xda')  # start of scan, then its header's length
    head_end = start + 2 + int.from_bytes(data[start + 2:start + 4], 'big')
    return data[:head_end], _RESTART.split(data[head_end:-2])  # -2: the end-of-image marker


def join_jpeg(head: bytes, rows: list[bytes]) -> bytes:
    """The inverse of split_jpeg: rows numbered RST0..RST7 in turn, then end of image."""
    pieces = [head]
    for index, row in enumerate(rows[:-1]):
        pieces += (row, b'\xff' + bytes((0xD0 + index % 8,)))
    pieces += (rows[-1], b'\xff\xd9')
    return b''.join(pieces)


class SplicedJpeg:
    """JPEG frames of which usually only the top block rows change (the caption, not the view).

    A frame whose rows below `top` px are those of the last full encoding is encoded as the top
    rows alone, spliced in front of the stored coded rows: byte for byte the full encoding of the
    frame, at a tenth of the cost while the head is still.
    """

    def __init__(self, height: int, top: int) -> None:
        self.top = min(height, -(-top // BLOCK_ROWS) * BLOCK_ROWS)  # whole block rows
        self._height = height
        self._quality: int | None = None
        self._head = b''
        self._rows: list[bytes] = []

    def encode(self, frame: np.ndarray, quality: int, rest_unchanged: bool) -> bytes:
        """Frame (packed RGBX) as JPEG, encoding only its top rows when it can.

        rest_unchanged says its rows from `top` on are the last full encoding's.
        """
        if rest_unchanged and quality == self._quality and self.top < self._height:
            top_rows = split_jpeg(encode_jpeg(frame[:self.top], quality))[1]
            return join_jpeg(self._head, top_rows + self._rows[len(top_rows):])
        data = encode_jpeg(frame, quality)
        self._head, self._rows = split_jpeg(data)
        self._quality = quality
        return data


class CameraRenderer:
    """Renders width x height views of the panorama for a pan and tilt (rad) and encodes JPEG.

    Pixels are packed RGBX in one uint32 each, so a frame is a single np.take of precomputed
    indices into a flat panorama (about 0.5 ms at 640x480, fancy indexing of RGB rows took 6 ms)
    into a frame buffer that is reused. While pan and tilt stay the same, only the rows under the
    caption are taken and encoded again (SplicedJpeg).
    """

    def __init__(self, width: int = 640, height: int = 480, horizontal_fov: float = math.radians(48.7),
                 panorama: np.ndarray | None = None,
                 landmarks: Sequence[tuple[float, tuple[int, int, int], str]] = LANDMARKS) -> None:
        """panorama: the scene behind everything (default: the scene with these landmarks)."""
        if width < 16 or height < 16:
            raise ValueError(f'image size {width}x{height} is too small (at least 16x16)')
        if not 0.05 < horizontal_fov < math.radians(170):
            raise ValueError(f'horizontal field of view {math.degrees(horizontal_fov):.1f} deg '
                             'is outside (3, 170) deg')
        self.width, self.height = width, height
        self.fx = self.fy = focal_length(width, horizontal_fov)
        self.cx, self.cy = (width - 1) / 2, (height - 1) / 2
        self.pinhole = Pinhole(self.fx, self.fy, self.cx, self.cy)
        self._pixels = scene_pixels(landmarks) if panorama is None else packed_panorama(panorama)
        self._frame = np.empty((height, width), dtype=np.uint32)
        self._index = np.empty((height, width), dtype=np.intp)
        self._tilt: float | None = None
        self._lookups = 0  # lookups built so far: a frame's view is (pan shift, this count)
        self._frame_view: tuple[int, int] | None = None
        self._frame_scene: tuple[object, ...] | None = None
        self.placed: Placed | None = None  # where the last jpeg() drew its scene's ball and person
        self._rays: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None
        self._caption = CaptionWriter(_font(16))
        self._jpeg = SplicedJpeg(height, CAPTION_AT[1] + self._caption.line_height + CAPTION_MARGIN[1])

    def _rebuild(self, tilt: float) -> None:
        # The image is mirror-symmetric about its centre column (cx is the middle): compute the
        # right half (with the middle column of an odd width) and mirror it into the left half.
        half = self.width // 2
        if self._rays is None:
            u = (np.arange(half, self.width, dtype=np.float32) - self.cx) / self.fx
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
        columns = np.rint(azimuth * np.float32(PANORAMA_WIDTH / (2 * math.pi))).astype(np.intp)
        rows = np.rint((np.float32(math.pi / 2) - elevation) * np.float32(PANORAMA_HEIGHT / math.pi))
        rows = np.clip(rows, 0, PANORAMA_HEIGHT - 1).astype(np.intp) * (2 * PANORAMA_WIDTH)
        # A mirrored ray has the opposite azimuth and the same elevation.
        self._index[:, half:] = rows + columns % PANORAMA_WIDTH
        self._index[:, :half] = (rows + (-columns) % PANORAMA_WIDTH)[:, ::-1][:, :half]
        self._tilt = tilt
        self._lookups += 1

    def _view_of(self, pan: float, tilt: float) -> tuple[int, int]:
        """(pan shift in panorama columns, lookup count) of the view at pan, tilt."""
        if self._tilt is None or abs(tilt - self._tilt) > TILT_STEP:
            self._rebuild(tilt)
        return round(pan * PANORAMA_WIDTH / (2 * math.pi)) % PANORAMA_WIDTH, self._lookups

    def place(self, scene: SceneView, pan: float, tilt: float) -> Placed:
        """Where the scene's ball and person are in the view at pan, tilt."""
        ball = None
        if scene.ball is not None:
            centre = self.pinhole.project(*scene.ball, pan, tilt)
            if centre is not None:
                ball = (*centre, self.fx * math.tan(BALL_RADIUS))
        keypoints = {}
        for name, direction in (scene.person or {}).items():
            point = self.pinhole.project(*direction, pan, tilt)
            if point is not None:
                keypoints[name] = point
        return Placed(ball, keypoints, self.fx / PERSON_DISTANCE)

    def render(self, pan: float, tilt: float, scene: SceneView | None = None) -> np.ndarray:
        """RGB array height x width x 3 of the view at pan, tilt, with the scene drawn (a new array)."""
        shift, _ = self._view_of(pan, tilt)
        # Every index is in range by construction, so 'clip' only spares numpy's bounds check.
        frame = self._pixels[shift:].take(self._index, mode='clip')
        if scene is not None:
            self._draw(frame, self.place(scene, pan, tilt))
        return frame.view(np.uint8).reshape(self.height, self.width, 4)[..., :3].copy()

    @staticmethod
    def _draw(frame: np.ndarray, placed: Placed) -> None:
        if placed.keypoints:
            draw_person(frame, placed.keypoints, placed.person_scale)
        if placed.ball is not None:
            draw_ball(frame, *placed.ball)

    def jpeg(self, pan: float, tilt: float, caption: str, quality: int = 80,
             scene: SceneView | None = None) -> bytes:
        """The view with the scene drawn and `caption` (frame counter and time) in the top-left corner.

        Where the scene's things were drawn is kept as .placed (None without a scene).
        """
        view = self._view_of(pan, tilt)
        placed = self.place(scene, pan, tilt) if scene is not None else None
        signature = placed.signature if placed is not None else None
        unchanged = view == self._frame_view and signature == self._frame_scene
        # The same view: only the rows under the caption need their clean pixels back (and the
        # scene drawn again over them: the same pixels below, where they are already).
        rows = self._jpeg.top if unchanged else self.height
        np.take(self._pixels[view[0]:], self._index[:rows], out=self._frame[:rows], mode='clip')
        if placed is not None:
            self._draw(self._frame, placed)
        self._frame_view, self._frame_scene, self.placed = view, signature, placed
        self._caption.draw(self._frame, caption, *CAPTION_AT)
        return self._jpeg.encode(self._frame, quality, unchanged)

    def annotated_jpeg(self, keypoints: Mapping[str, tuple[float, float]], quality: int = 80) -> bytes:
        """The last frame jpeg() made, with the skeleton of keypoints drawn as the gesture app does."""
        frame = self._frame.copy()
        draw_skeleton(frame, keypoints)
        return encode_jpeg(frame, quality)
