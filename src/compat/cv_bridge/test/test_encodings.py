"""Encodings and conversions as plain functions, on small arrays whose answers are known."""

import numpy as np
import pytest
from cv_bridge.encodings import check_image, convert, cv_type_of, parse_encoding, rescale_depth
from cv_bridge.error import CvBridgeError


@pytest.mark.parametrize(('name', 'dtype', 'channels', 'order'), [
    ('mono8', np.uint8, 1, 'GRAY'), ('mono16', np.uint16, 1, 'GRAY'),
    ('bgr8', np.uint8, 3, 'BGR'), ('rgb8', np.uint8, 3, 'RGB'),
    ('bgra8', np.uint8, 4, 'BGRA'), ('rgba8', np.uint8, 4, 'RGBA'),
    ('8UC3', np.uint8, 3, None), ('8SC1', np.int8, 1, None), ('16SC2', np.int16, 2, None),
    ('32SC1', np.int32, 1, None), ('32FC1', np.float32, 1, None), ('64FC4', np.float64, 4, None),
])
def test_encodings_name_a_type_channels_and_order(name, dtype, channels, order):
    encoding = parse_encoding(name)
    assert (encoding.dtype, encoding.channels, encoding.order) == (np.dtype(dtype), channels, order)


@pytest.mark.parametrize(('name', 'message'), [
    ('yuv422', "unsupported encoding 'yuv422'; supported: mono8, mono16, bgr8"),
    ('bayer_rggb8', "unsupported encoding 'bayer_rggb8'"),
    ('8UC5', "unsupported encoding '8UC5'"),
    ('', "unsupported encoding '' (an empty encoding: was the message filled in?)"),
    (None, 'an encoding is a string such as bgr8, not NoneType'),
])
def test_unknown_encodings_are_named_in_the_error(name, message):
    with pytest.raises(CvBridgeError) as error:
        parse_encoding(name)
    assert str(error.value).startswith(message)


def test_opencv_type_of_an_array():
    assert cv_type_of(np.zeros((2, 3), np.uint8)) == '8UC1'
    assert cv_type_of(np.zeros((2, 3, 1), np.uint16)) == '16UC1'
    assert cv_type_of(np.zeros((2, 3, 4), np.float64)) == '64FC4'
    assert cv_type_of(np.zeros((2, 3, 2), np.dtype('>i2'))) == '16SC2'


@pytest.mark.parametrize(('value', 'message'), [
    ([[1, 2]], 'expected an OpenCV image (a numpy array), not list'),
    (np.uint8(3), 'expected an OpenCV image (a numpy array), not uint8'),
    (np.zeros(5, np.uint8), 'an image array has the shape (height, width) or (height, width, channels), '
                            'not (5,)'),
    (np.zeros((2, 2, 2, 2), np.uint8), 'an image array has the shape (height, width) or (height, width, '
                                       'channels), not (2, 2, 2, 2)'),
    (np.zeros((2, 2, 5), np.uint8), 'an image has 1 to 4 channels, not 5 (shape (2, 2, 5))'),
    (np.zeros((0, 4, 3), np.uint8), 'the image is empty (shape (0, 4, 3))'),
    (np.zeros((2, 2), bool), 'an image array of bool has no OpenCV type; use uint8'),
    (np.zeros((2, 2), np.int64), 'an image array of int64 has no OpenCV type'),
    (np.zeros((2, 2), np.complex64), 'an image array of complex64 has no OpenCV type'),
])
def test_arrays_that_cannot_be_images(value, message):
    with pytest.raises(CvBridgeError) as error:
        check_image(value)
    assert str(error.value).startswith(message)


# One pixel in each named encoding: white, and a pure red (BGR 0, 0, 255).
WHITE_RED = {
    'bgr8': [[[255, 255, 255], [0, 0, 255]]],
    'rgb8': [[[255, 255, 255], [255, 0, 0]]],
    'bgra8': [[[255, 255, 255, 255], [0, 0, 255, 255]]],
    'rgba8': [[[255, 255, 255, 255], [255, 0, 0, 255]]],
}


@pytest.mark.parametrize('source', list(WHITE_RED))
@pytest.mark.parametrize('target', list(WHITE_RED))
def test_colour_orders_convert_into_one_another(source, target):
    image = np.array(WHITE_RED[source], np.uint8)
    converted = convert(image, parse_encoding(source), parse_encoding(target))
    np.testing.assert_array_equal(converted, np.array(WHITE_RED[target], np.uint8))


@pytest.mark.parametrize('source', list(WHITE_RED))
def test_colour_to_grey_uses_the_luma_weights(source):
    grey = convert(np.array(WHITE_RED[source], np.uint8), parse_encoding(source), parse_encoding('mono8'))
    np.testing.assert_array_equal(grey, [[255, 76]])  # 0.299 * 255 for pure red
    grey16 = convert(np.array(WHITE_RED[source], np.uint8), parse_encoding(source), parse_encoding('mono16'))
    np.testing.assert_array_equal(grey16, [[65535, 76 * 257]])


def test_grey_to_colour_repeats_the_value_and_adds_opaque_alpha():
    grey = np.array([[0, 200]], np.uint8)
    bgr = convert(grey, parse_encoding('mono8'), parse_encoding('bgr8'))
    np.testing.assert_array_equal(bgr, [[[0, 0, 0], [200, 200, 200]]])
    rgba = convert(grey, parse_encoding('mono8'), parse_encoding('rgba8'))
    np.testing.assert_array_equal(rgba, [[[0, 0, 0, 255], [200, 200, 200, 255]]])
    from16 = convert(np.array([[65535, 257 * 10]], np.uint16), parse_encoding('mono16'),
                     parse_encoding('bgr8'))
    assert from16.dtype == np.uint8
    np.testing.assert_array_equal(from16, [[[255] * 3, [10] * 3]])


def test_depth_keeps_the_full_range():
    np.testing.assert_array_equal(rescale_depth(np.array([0, 1, 128, 255], np.uint8), np.dtype(np.uint16)),
                                  [0, 257, 32896, 65535])
    down = rescale_depth(np.array([0, 128, 32768, 65535], np.uint16), np.dtype(np.uint8))
    assert down.dtype == np.uint8
    np.testing.assert_array_equal(down, [0, 0, 128, 255])


def test_same_encoding_is_left_alone():
    image = np.arange(6, dtype=np.float32).reshape(2, 3)
    assert convert(image, parse_encoding('32FC1'), parse_encoding('32FC1')) is image


@pytest.mark.parametrize(('source', 'target'), [('8UC3', 'bgr8'), ('bgr8', '8UC3'), ('16UC1', 'mono8')])
def test_plain_opencv_types_do_not_convert(source, target):
    with pytest.raises(CvBridgeError, match=f'^cannot convert {source} to {target}: only mono8, '):
        convert(np.zeros((1, 1, 3), np.uint8), parse_encoding(source), parse_encoding(target))
