"""Where the red ball is in a camera image, and where to point the head to centre it: no ROS."""

import math

import cv2
import numpy as np

# Red in OpenCV's HSV (hue 0..179 covers the colour circle once): both ends of the hue range,
# saturated and bright, so orange, pink, skin and brown stay out.
RED_RANGES = (((0, 120, 70), (8, 255, 255)), ((172, 120, 70), (179, 255, 255)))


def red_mask(image: np.ndarray) -> np.ndarray:
    """255 where a BGR image is clearly red, 0 elsewhere."""
    hsv = cv2.cvtColor(image, cv2.COLOR_BGR2HSV)
    low_reds, high_reds = (cv2.inRange(hsv, np.array(low, dtype=np.uint8), np.array(high, dtype=np.uint8))
                           for low, high in RED_RANGES)
    return cv2.bitwise_or(low_reds, high_reds)


def find_red_ball(image: np.ndarray, min_area: float) -> tuple[float, float, float] | None:
    """(x, y, area) in px of the biggest red blob's centre and size, or None if none has min_area."""
    contours, _ = cv2.findContours(red_mask(image), cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_SIMPLE)
    if not contours:
        return None
    moments = cv2.moments(max(contours, key=cv2.contourArea))
    area = moments['m00']
    if area < min_area or area <= 0:
        return None
    return moments['m10'] / area, moments['m01'] / area, area


def angle_offsets(x: float, y: float, width: int, height: int,
                  horizontal_fov: float) -> tuple[float, float]:
    """(right, down): the angles in rad from the image's centre to the pixel (x, y).

    horizontal_fov is the camera's in rad (48.66 deg for the Olive camera's calibration).
    """
    focal = (width / 2) / math.tan(horizontal_fov / 2)
    return math.atan((x - (width - 1) / 2) / focal), math.atan((y - (height - 1) / 2) / focal)


def tracking_goals(pan: float, tilt: float, right: float, down: float, gain_pan: float,
                   gain_tilt: float) -> tuple[float, float]:
    """(pan, tilt) goals that turn the head a gain's share of the way to the ball.

    pan and tilt are where the servos are; the ball is `right` and `down` rad off the image's
    centre. Positive pan turns the head left and positive tilt turns the camera down, so a ball to
    the right lowers pan and a ball below raises tilt.
    """
    return pan - gain_pan * right, tilt + gain_tilt * down
