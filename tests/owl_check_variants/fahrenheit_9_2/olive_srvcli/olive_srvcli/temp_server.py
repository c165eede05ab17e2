"""temp_server with the listing's 9 / 2: owl check must fail it."""

import rclpy
from olive_interfaces.srv import TempConv
from rclpy.executors import ExternalShutdownException
from rclpy.node import Node


class TempService(Node):
    def __init__(self):
        super().__init__('temp_service')
        self.srv = self.create_service(TempConv, 'temp_conversion', self.temp_conversion_callback)

    def temp_conversion_callback(self, request, response):
        response.temp_k = request.temp_c + 273.15
        response.temp_f = (request.temp_c * 9 / 2) + 32
        return response


def main(args=None):
    rclpy.init(args=args)
    node = TempService()
    try:
        rclpy.spin(node)
    except (KeyboardInterrupt, ExternalShutdownException):
        pass
    node.destroy_node()
    rclpy.try_shutdown()
