"""A student's OpenCV viewer loop as section 4.5 shows windows: cv2.imshow, then cv2.waitKey(1).

Shows a 160x120 image (left half red, right half a grey that changes with every frame) in the
window 'camera', prints each key it gets, and at Ctrl-C how many frames it showed.
"""

import cv2
import numpy as np

image = np.zeros((120, 160, 3), np.uint8)
image[:, :80] = (0, 0, 255)
frames = 0
try:
    while True:
        image[:, 80:] = frames % 256
        cv2.imshow('camera', image)
        key = cv2.waitKey(1)
        if key != -1:
            print(f'key {key}', flush=True)
        frames += 1
except KeyboardInterrupt:
    pass
finally:
    cv2.destroyAllWindows()
print(f'shown {frames} frames', flush=True)
