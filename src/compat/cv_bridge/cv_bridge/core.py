"""CvBridge: sensor_msgs images <-> OpenCV images (numpy arrays), with upstream's method names."""

from __future__ import annotations

import numpy as np
from sensor_msgs.msg import CompressedImage, Image
from std_msgs.msg import Header

from .compressed import decode, decoded_encoding, encode
from .encodings import PASSTHROUGH, check_image, convert, cv_type_of, parse_encoding
from .error import CvBridgeError
from .pixels import image_from_buffer, image_to_buffer, is_big_endian

# What to use instead when one image message type is given to the other's method.
OTHER_METHOD = {Image: ' (for an Image, use imgmsg_to_cv2)',
                CompressedImage: ' (for a CompressedImage, use compressed_imgmsg_to_cv2)'}


def require_message(msg: object, kind: type, method: str) -> None:
    """Raise CvBridgeError unless msg is a kind; for the other image type it names the method to use."""
    if not isinstance(msg, kind):
        raise CvBridgeError(f'{method} takes a sensor_msgs/msg/{kind.__name__}, not '
                            f'{type(msg).__name__}{OTHER_METHOD.get(type(msg), "")}')


def plural(count: int, noun: str) -> str:
    """'1 channel' or '3 channels': a count with its noun, for error messages."""
    return f'{count} {noun}' if count == 1 else f'{count} {noun}s'


def target_encoding(desired_encoding: object, source_name: str) -> object:
    """The encoding to convert to: the source's own for 'passthrough', else desired_encoding as given."""
    return source_name if desired_encoding == PASSTHROUGH else desired_encoding


class CvBridge:
    """Converts between ROS 2 image messages and OpenCV images, as ROS 2's cv_bridge does.

    Every method raises CvBridgeError, with a one-line reason, for input it cannot convert.
    """

    def imgmsg_to_cv2(self, img_msg: Image, desired_encoding: str = PASSTHROUGH) -> np.ndarray:
        """A new array of a sensor_msgs/msg/Image's pixels, in desired_encoding's layout.

        desired_encoding fixes the channel order and depth; 'passthrough' keeps them as the message has them.
        """
        require_message(img_msg, Image, 'imgmsg_to_cv2')
        source = parse_encoding(img_msg.encoding)
        target = parse_encoding(target_encoding(desired_encoding, source.name))
        image = image_from_buffer(img_msg.data, img_msg.height, img_msg.width, img_msg.step, source,
                                  bool(img_msg.is_bigendian))
        return convert(image, source, target)

    def cv2_to_imgmsg(self, cvim: np.ndarray, encoding: str = PASSTHROUGH,
                      header: Header | None = None) -> Image:
        """A sensor_msgs/msg/Image of an array, its pixels as they are.

        encoding names what the pixels already are (bgr8 for OpenCV's colour images) and must fit the
        array's type and channels; 'passthrough' names the array's OpenCV type, such as 8UC3.
        """
        image = check_image(cvim)
        cv_type = cv_type_of(image)
        if encoding != PASSTHROUGH:
            wanted = parse_encoding(encoding)
            if wanted.cv_type != cv_type:
                raise CvBridgeError(f'encoding {encoding} needs a {wanted.dtype} image with '
                                    f'{plural(wanted.channels, "channel")} ({wanted.cv_type}), but this '
                                    f'one is {cv_type} ({image.dtype}, shape {image.shape})')
        if header is not None and not isinstance(header, Header):
            raise CvBridgeError(f'header must be a std_msgs/msg/Header, not {type(header).__name__}')
        data, step = image_to_buffer(image)
        return Image(header=header if header is not None else Header(), height=image.shape[0],
                     width=image.shape[1], encoding=cv_type if encoding == PASSTHROUGH else encoding,
                     is_bigendian=is_big_endian(image.dtype), step=step, data=data)

    def compressed_imgmsg_to_cv2(self, cmprs_img_msg: CompressedImage,
                                 desired_encoding: str = PASSTHROUGH) -> np.ndarray:
        """The image in a sensor_msgs/msg/CompressedImage, converted to desired_encoding.

        With 'passthrough' it comes as decoded: BGR(A) for colour.
        """
        require_message(cmprs_img_msg, CompressedImage, 'compressed_imgmsg_to_cv2')
        image = decode(cmprs_img_msg.data, cmprs_img_msg.format)
        source = decoded_encoding(image)
        return convert(image, source, parse_encoding(target_encoding(desired_encoding, source.name)))

    def cv2_to_compressed_imgmsg(self, cvim: np.ndarray, dst_format: str = 'jpg') -> CompressedImage:
        """A sensor_msgs/msg/CompressedImage of an array (BGR(A) if colour), as jpg, jpeg or png.

        Its format field is dst_format, as upstream sets it.
        """
        data = encode(check_image(cvim), dst_format)
        return CompressedImage(format=dst_format, data=data)
