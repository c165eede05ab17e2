"""The one exception every CvBridge method raises for input it cannot convert."""


class CvBridgeError(TypeError):
    """Raised by CvBridge for input it cannot convert; str() says why in one line.

    A TypeError, as upstream's is, so `except TypeError` written for upstream still catches it.
    """
