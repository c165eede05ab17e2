import rclpy
from rclpy.node import Node
from olive_interfaces.srv import TempConv


class TempService(Node):

    def __init__(self):
        super().__init__('temp_service')
        self.srv = self.create_service(TempConv, 'temp_conversion',
                                      self.temp_conversion_callback)

    def temp_conversion_callback(self, request, response):
        response.temp_k = request.temp_c + 273.15
        response.temp_f = (request.temp_c * 9 / 2) + 32

        self.get_logger().info(
            f'Incoming request \n Temperature in Celsius: {request.temp_c}'
        )
        return response


def main():
    rclpy.init()
    temp_service = TempService()
    rclpy.spin(temp_service)
    rclpy.shutdown()

if __name__ == '__main__':
    main()
