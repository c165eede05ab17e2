"""temp_client CELSIUS: ask temp_conversion for Kelvin and Fahrenheit (the course's section 3.6)."""

import rclpy
from olive_interfaces.srv import TempConv
from rclpy.node import Node

from olive_srvcli.command_line import argument_or_exit, celsius_argument


class TempClient(Node):

    def __init__(self) -> None:
        super().__init__('temp_client')
        self.cli = self.create_client(TempConv, 'temp_conversion')
        while not self.cli.wait_for_service(timeout_sec=1.0):
            self.get_logger().info('service not available, waiting again..')
        self.req = TempConv.Request()

    def send_request(self, temp_c: float) -> TempConv.Response:
        self.req.temp_c = temp_c
        self.future = self.cli.call_async(self.req)
        rclpy.spin_until_future_complete(self, self.future)
        return self.future.result()


def main(args: list[str] | None = None) -> None:
    # The course's float(sys.argv[1]), checked: a bad command line ends here with one line, code 2.
    temp_c = argument_or_exit(celsius_argument, '<celsius>', args)
    rclpy.init(args=args)
    temp_client = None
    try:
        temp_client = TempClient()  # waits for the server
        response = temp_client.send_request(temp_c)
        temp_client.get_logger().info(
            f'The Temperature of {temp_c} Celsius is equal to {response.temp_k} Kelvin '
            f'and {response.temp_f} Fahrenheit')
    except KeyboardInterrupt:
        pass  # Ctrl-C while it waits for the server
    finally:
        if temp_client is not None:
            temp_client.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
