import rclpy
from rclpy.node import Node
import sys
from olive_interfaces.srv import TempConv


class TempClient(Node):

    def __init__(self):
        super().__init__('temp_client')
        self.cli = self.create_client(TempConv, 'temp_conversion')
        while not self.cli.wait_for_service(timeout_sec=1.0):
            self.get_logger().info('service not available, waiting again..')
        self.req = TempConv.Request()

    def send_request(self, temp_c):
        self.req.temp_c = temp_c
        self.future = self.cli.call_async(self.req)
        rclpy.spin_until_future_complete(self, self.future)
        return self.future.result()


def main():
    rclpy.init()
    temp_client = TempClient()
    response = temp_client.send_request(float(sys.argv[1]))
    temp_client.get_logger().info(
        f'The Temperature of {float(sys.argv[1])} Celsius is equal to {response.temp_k} Kelvin and {response.temp_f} Fahrenheit'
    )

    temp_client.destroy_node()
    rclpy.shutdown()

if __name__ == '__main__':
    main()
