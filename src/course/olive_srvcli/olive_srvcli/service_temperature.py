"""temp_server: convert a Celsius temperature into Kelvin and Fahrenheit (service temp_conversion)."""

import signal

import rclpy
from olive_interfaces.srv import TempConv
from rclpy.node import Node

from olive_srvcli.conversions import celsius_to_fahrenheit, celsius_to_kelvin, check_celsius


class TempService(Node):

    def __init__(self) -> None:
        super().__init__('temp_service')
        self.srv = self.create_service(TempConv, 'temp_conversion', self.temp_conversion_callback)

    def temp_conversion_callback(self, request: TempConv.Request,
                                 response: TempConv.Response) -> TempConv.Response:
        self.get_logger().info(f'Incoming request\nTemperature in Celsius: {request.temp_c}')
        problem = check_celsius(request.temp_c)
        if problem:
            # TempConv has no error field; NaN says "no answer" without inventing one.
            self.get_logger().warn(f'Refusing request: {problem}')
            response.temp_k = response.temp_f = float('nan')
            return response
        response.temp_k = celsius_to_kelvin(request.temp_c)
        response.temp_f = celsius_to_fahrenheit(request.temp_c)
        return response


def main(args: list[str] | None = None) -> None:
    rclpy.init(args=args)
    temp_service = None
    try:
        temp_service = TempService()
        rclpy.spin(temp_service)
    except KeyboardInterrupt:
        pass  # Ctrl-C is how the course stops a node
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C must not stop the clean-up
        if temp_service is not None:
            temp_service.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
