"""CvBridge round trips through real sensor_msgs messages, and its errors for bad input."""

import numpy as np
import pytest
from cv_bridge import CvBridge, CvBridgeError
from rclpy.serialization import deserialize_message, serialize_message
from sensor_msgs.msg import CompressedImage, Image
from std_msgs.msg import Header

BRIDGE = CvBridge()
JPEG_MAGIC = b'\xff\xd8\xff'
PNG_MAGIC = b'\x89PNG\r\n\x1a\n'


def random_image(shape, dtype, seed=1):
    rng = np.random.default_rng(seed)
    if np.dtype(dtype).kind == 'f':
        return rng.standard_normal(shape).astype(dtype)
    info = np.iinfo(dtype)
    return rng.integers(info.min, info.max, size=shape, endpoint=True, dtype=dtype)


def over_the_wire(msg):
    """The message as a subscriber receives it (data as rclpy's array.array)."""
    return deserialize_message(serialize_message(msg), type(msg))


def test_the_error_is_a_type_error_as_upstream():
    assert issubclass(CvBridgeError, TypeError)


@pytest.mark.parametrize(('encoding', 'shape', 'dtype'), [
    ('mono8', (4, 5), np.uint8), ('mono16', (4, 5), np.uint16), ('bgr8', (4, 5, 3), np.uint8),
    ('rgb8', (4, 5, 3), np.uint8), ('bgra8', (4, 5, 4), np.uint8), ('rgba8', (4, 5, 4), np.uint8),
])
def test_named_encodings_round_trip(encoding, shape, dtype):
    image = random_image(shape, dtype)
    msg = over_the_wire(BRIDGE.cv2_to_imgmsg(image, encoding))
    channels = 1 if len(shape) == 2 else shape[2]
    assert (msg.encoding, msg.height, msg.width) == (encoding, 4, 5)
    assert msg.step == 5 * channels * np.dtype(dtype).itemsize
    assert not msg.is_bigendian
    for desired in ('passthrough', encoding):
        back = BRIDGE.imgmsg_to_cv2(msg, desired)
        assert back.dtype == dtype
        np.testing.assert_array_equal(back, image)


@pytest.mark.parametrize('dtype', [np.uint8, np.int8, np.uint16, np.int16, np.int32, np.float32, np.float64])
@pytest.mark.parametrize('channels', [1, 2, 3, 4])
def test_passthrough_round_trips_every_opencv_type(dtype, channels):
    image = random_image((3, 2, channels), dtype)
    msg = over_the_wire(BRIDGE.cv2_to_imgmsg(image))
    depth = {'u': 'U', 'i': 'S', 'f': 'F'}[np.dtype(dtype).kind]
    assert msg.encoding == f'{np.dtype(dtype).itemsize * 8}{depth}C{channels}'
    back = BRIDGE.imgmsg_to_cv2(msg)
    assert back.shape == ((3, 2) if channels == 1 else (3, 2, channels))
    np.testing.assert_array_equal(back.reshape(image.shape), image)


def test_rgb_message_becomes_a_bgr_array_and_other_conversions():
    rgb = random_image((2, 3, 3), np.uint8)
    msg = BRIDGE.cv2_to_imgmsg(rgb, 'rgb8')
    np.testing.assert_array_equal(BRIDGE.imgmsg_to_cv2(msg, 'bgr8'), rgb[:, :, ::-1])
    bgra = BRIDGE.imgmsg_to_cv2(msg, 'bgra8')
    np.testing.assert_array_equal(bgra[:, :, :3], rgb[:, :, ::-1])
    assert (bgra[:, :, 3] == 255).all()
    mono16 = BRIDGE.cv2_to_imgmsg(np.array([[0, 65535, 32768]], np.uint16), 'mono16')
    np.testing.assert_array_equal(BRIDGE.imgmsg_to_cv2(mono16, 'mono8'), [[0, 255, 128]])


def test_the_array_is_a_copy_of_the_data():
    msg = BRIDGE.cv2_to_imgmsg(np.zeros((2, 2), np.uint8), 'mono8')
    image = BRIDGE.imgmsg_to_cv2(msg)
    image[0, 0] = 9
    assert msg.data[0] == 0
    assert image.flags.writeable


def test_cv2_to_imgmsg_writes_the_pixels_as_they_are():
    bgr = random_image((2, 3, 3), np.uint8)
    msg = BRIDGE.cv2_to_imgmsg(bgr, 'rgb8')  # upstream labels the data; it does not reorder it
    assert bytes(msg.data) == bgr.tobytes()
    transposed = random_image((3, 2, 3), np.uint8).transpose(1, 0, 2)  # not C-contiguous
    np.testing.assert_array_equal(BRIDGE.imgmsg_to_cv2(BRIDGE.cv2_to_imgmsg(transposed, 'bgr8')), transposed)


def test_rows_padded_by_step_and_an_unpadded_last_row():
    # 2x3 mono8 with rows of 4 bytes: the fourth byte of each row is padding.
    msg = Image(height=2, width=3, encoding='mono8', step=4, data=bytes([1, 2, 3, 99, 4, 5, 6, 99]))
    np.testing.assert_array_equal(BRIDGE.imgmsg_to_cv2(msg), [[1, 2, 3], [4, 5, 6]])
    msg.data = bytes([1, 2, 3, 99, 4, 5, 6])
    np.testing.assert_array_equal(BRIDGE.imgmsg_to_cv2(msg), [[1, 2, 3], [4, 5, 6]])
    colour = Image(height=1, width=2, encoding='rgb8', step=8, data=bytes([1, 2, 3, 4, 5, 6, 0, 0]))
    np.testing.assert_array_equal(BRIDGE.imgmsg_to_cv2(colour, 'bgr8'), [[[3, 2, 1], [6, 5, 4]]])


def test_big_endian_data_is_read_and_written():
    values = np.array([[1, 258, 65535]], np.uint16)
    msg = Image(height=1, width=3, encoding='mono16', step=6, is_bigendian=True,
                data=values.astype('>u2').tobytes())
    back = BRIDGE.imgmsg_to_cv2(msg)
    assert back.dtype == np.uint16
    assert back.dtype.isnative
    np.testing.assert_array_equal(back, values)
    big = BRIDGE.cv2_to_imgmsg(values.astype('>u2'), 'mono16')
    assert big.is_bigendian
    assert bytes(big.data) == values.astype('>u2').tobytes()
    np.testing.assert_array_equal(BRIDGE.imgmsg_to_cv2(big), values)
    little = BRIDGE.cv2_to_imgmsg(values, 'mono16')
    assert not little.is_bigendian
    assert bytes(little.data) == values.astype('<u2').tobytes()


def test_header_is_copied_in():
    header = Header(frame_id='camera')
    header.stamp.sec = 12
    msg = BRIDGE.cv2_to_imgmsg(np.zeros((1, 1), np.uint8), header=header)
    assert (msg.header.frame_id, msg.header.stamp.sec) == ('camera', 12)
    assert BRIDGE.cv2_to_imgmsg(np.zeros((1, 1), np.uint8)).header == Header()


@pytest.mark.parametrize(('shape', 'dtype', 'dst_format'), [
    ((6, 7), np.uint8, 'png'), ((6, 7), np.uint16, 'png'), ((6, 7, 3), np.uint8, 'png'),
    ((6, 7, 4), np.uint8, 'png'), ((6, 7, 4), np.uint16, 'png'),
])
def test_png_round_trips_exactly(shape, dtype, dst_format):
    image = random_image(shape, dtype)
    msg = over_the_wire(BRIDGE.cv2_to_compressed_imgmsg(image, dst_format))
    assert msg.format == 'png'
    assert bytes(msg.data).startswith(PNG_MAGIC)
    back = BRIDGE.compressed_imgmsg_to_cv2(msg)
    assert back.dtype == dtype
    np.testing.assert_array_equal(back, image)


@pytest.mark.parametrize('dst_format', ['jpg', 'jpeg'])
@pytest.mark.parametrize('shape', [(16, 16), (16, 16, 3)])
def test_jpeg_round_trips_closely(dst_format, shape):
    image = np.full(shape, 100, np.uint8)
    image[4:12, 4:12] = 180
    msg = BRIDGE.cv2_to_compressed_imgmsg(image, dst_format)
    assert msg.format == dst_format
    assert bytes(msg.data).startswith(JPEG_MAGIC)
    back = BRIDGE.compressed_imgmsg_to_cv2(over_the_wire(msg))
    assert back.shape == image.shape
    assert back.dtype == np.uint8
    assert np.abs(back.astype(int) - image).mean() < 3


def test_the_default_compressed_format_is_jpg():
    assert BRIDGE.cv2_to_compressed_imgmsg(np.zeros((8, 8, 3), np.uint8)).format == 'jpg'


def test_compressed_images_convert_to_the_desired_encoding():
    bgr = random_image((5, 4, 3), np.uint8)
    msg = BRIDGE.cv2_to_compressed_imgmsg(bgr, 'png')
    np.testing.assert_array_equal(BRIDGE.compressed_imgmsg_to_cv2(msg, 'bgr8'), bgr)
    np.testing.assert_array_equal(BRIDGE.compressed_imgmsg_to_cv2(msg, 'rgb8'), bgr[:, :, ::-1])
    assert BRIDGE.compressed_imgmsg_to_cv2(msg, 'mono8').shape == (5, 4)
    grey = BRIDGE.cv2_to_compressed_imgmsg(np.array([[0, 200]], np.uint8), 'png')
    np.testing.assert_array_equal(BRIDGE.compressed_imgmsg_to_cv2(grey, 'bgr8'), [[[0] * 3, [200] * 3]])
    grey16 = BRIDGE.cv2_to_compressed_imgmsg(np.array([[65535]], np.uint16), 'png')
    np.testing.assert_array_equal(BRIDGE.compressed_imgmsg_to_cv2(grey16, 'mono8'), [[255]])


def test_the_simulated_cameras_frames_decode():
    # olive_sim's camera publishes Pillow JPEGs with format 'jpeg'; the course displays them.
    from io import BytesIO

    from PIL import Image as PillowImage
    buffer = BytesIO()
    PillowImage.new('RGB', (32, 24), (255, 0, 0)).save(buffer, format='JPEG')
    frame = BRIDGE.compressed_imgmsg_to_cv2(CompressedImage(format='jpeg', data=buffer.getvalue()))
    assert frame.shape == (24, 32, 3)
    blue, green, red = frame[12, 16].astype(int)
    assert red > 240
    assert blue < 15
    assert green < 15  # BGR order, as cv2.imshow wants


IMAGE = np.zeros((2, 3, 3), np.uint8)


@pytest.mark.parametrize(('call', 'message'), [
    (lambda: BRIDGE.imgmsg_to_cv2(CompressedImage()),
     'imgmsg_to_cv2 takes a sensor_msgs/msg/Image, not CompressedImage (for a CompressedImage, use '
     'compressed_imgmsg_to_cv2)'),
    (lambda: BRIDGE.compressed_imgmsg_to_cv2(Image()),
     'compressed_imgmsg_to_cv2 takes a sensor_msgs/msg/CompressedImage, not Image (for an Image, use '
     'imgmsg_to_cv2)'),
    (lambda: BRIDGE.imgmsg_to_cv2('frame'), 'imgmsg_to_cv2 takes a sensor_msgs/msg/Image, not str'),
    (lambda: BRIDGE.imgmsg_to_cv2(Image()), "unsupported encoding '' (an empty encoding"),
    (lambda: BRIDGE.imgmsg_to_cv2(Image(encoding='yuv422', height=1, width=1, step=2, data=b'ab')),
     "unsupported encoding 'yuv422'; supported: mono8, mono16, bgr8, rgb8, bgra8, rgba8, passthrough"),
    (lambda: BRIDGE.imgmsg_to_cv2(BRIDGE.cv2_to_imgmsg(IMAGE, 'bgr8'), 'hsv'), "unsupported encoding 'hsv'"),
    (lambda: BRIDGE.imgmsg_to_cv2(BRIDGE.cv2_to_imgmsg(IMAGE), 'bgr8'),
     'cannot convert 8UC3 to bgr8: only mono8, mono16, bgr8, rgb8, bgra8, rgba8 convert into one another'),
    (lambda: BRIDGE.imgmsg_to_cv2(Image(encoding='mono8', height=0, width=3, step=3)),
     'the image is empty (3x0)'),
    (lambda: BRIDGE.imgmsg_to_cv2(Image(encoding='bgr8', height=2, width=3, step=6, data=bytes(18))),
     'step 6 is shorter than a row of 3 bgr8 pixels (9 bytes)'),
    (lambda: BRIDGE.imgmsg_to_cv2(Image(encoding='mono16', height=2, width=3, step=6, data=bytes(11))),
     '11 bytes of data are too few for a 3x2 mono16 image with step 6 (it needs 12)'),
    (lambda: BRIDGE.cv2_to_imgmsg([[1, 2]]), 'expected an OpenCV image (a numpy array), not list'),
    (lambda: BRIDGE.cv2_to_imgmsg(np.zeros(4, np.uint8)), 'an image array has the shape (height, width)'),
    (lambda: BRIDGE.cv2_to_imgmsg(np.zeros((2, 2), np.int64)), 'an image array of int64 has no OpenCV type'),
    (lambda: BRIDGE.cv2_to_imgmsg(IMAGE, 'mono8'),
     'encoding mono8 needs a uint8 image with 1 channel (8UC1), but this one is 8UC3 (uint8, '
     'shape (2, 3, 3))'),
    (lambda: BRIDGE.cv2_to_imgmsg(IMAGE.astype(np.uint16), 'bgr8'),
     'encoding bgr8 needs a uint8 image with 3 channels (8UC3), but this one is 16UC3'),
    (lambda: BRIDGE.cv2_to_imgmsg(IMAGE, 'bayer_rggb8'), "unsupported encoding 'bayer_rggb8'"),
    (lambda: BRIDGE.cv2_to_imgmsg(IMAGE, header='camera'), 'header must be a std_msgs/msg/Header, not str'),
    (lambda: BRIDGE.cv2_to_compressed_imgmsg(IMAGE, 'gif'),
     "unsupported compressed format 'gif'; supported: jpg, jpeg, png"),
    (lambda: BRIDGE.cv2_to_compressed_imgmsg(IMAGE, None), 'unsupported compressed format None'),
    (lambda: BRIDGE.cv2_to_compressed_imgmsg(IMAGE.astype(np.float32), 'png'),
     'png holds uint8 or uint16 images, not float32'),
    (lambda: BRIDGE.cv2_to_compressed_imgmsg(IMAGE.astype(np.uint16)), 'jpg holds uint8 images, not uint16'),
    (lambda: BRIDGE.cv2_to_compressed_imgmsg(np.zeros((2, 2, 2), np.uint8), 'png'),
     'png holds images of 1, 3 or 4 channels, not 2'),
    (lambda: BRIDGE.cv2_to_compressed_imgmsg('image.png'),
     'expected an OpenCV image (a numpy array), not str'),
    (lambda: BRIDGE.compressed_imgmsg_to_cv2(CompressedImage(format='jpeg')),
     'the compressed image has no data'),
    (lambda: BRIDGE.compressed_imgmsg_to_cv2(CompressedImage(format='jpeg', data=b'not an image at all')),
     "cannot decode 19 bytes of compressed image (format 'jpeg'): not an image OpenCV reads"),
    (lambda: BRIDGE.compressed_imgmsg_to_cv2(BRIDGE.cv2_to_compressed_imgmsg(IMAGE), 'mono32'),
     "unsupported encoding 'mono32'"),
])
def test_bad_input_is_one_clear_line(call, message):
    with pytest.raises(CvBridgeError) as error:
        call()
    assert str(error.value).startswith(message)
    assert '\n' not in str(error.value)
