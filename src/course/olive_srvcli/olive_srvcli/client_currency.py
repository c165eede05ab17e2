"""currency_client EUROS: ask currency_conversion for dollars, pounds and Swiss francs."""

import sys

import rclpy
from olive_interfaces.srv import CurrencyConv
from rclpy.node import Node

from olive_srvcli.command_line import argument_or_exit, euros_argument


class CurrencyClient(Node):

    def __init__(self) -> None:
        super().__init__('currency_client')
        self.cli = self.create_client(CurrencyConv, 'currency_conversion')
        while not self.cli.wait_for_service(timeout_sec=1.0):
            self.get_logger().info('service not available, waiting again..')
        self.req = CurrencyConv.Request()

    def send_request(self, euros: float) -> CurrencyConv.Response:
        self.req.euros = euros
        self.future = self.cli.call_async(self.req)
        rclpy.spin_until_future_complete(self, self.future)
        return self.future.result()


def main(args: list[str] | None = None) -> None:
    euros = argument_or_exit(euros_argument, '<euros>', args)  # a bad one: one line, exit code 2
    rclpy.init(args=args)
    currency_client = None
    try:
        currency_client = CurrencyClient()  # waits for the server
        response = currency_client.send_request(euros)
        if not response.success:
            currency_client.get_logger().error(f'The server refused: {response.message}')
            sys.exit(1)
        currency_client.get_logger().info(
            f'{euros} Euros are {response.dollars} US dollars, {response.pounds} British pounds '
            f'and {response.swiss_francs} Swiss francs')
    except KeyboardInterrupt:
        pass  # Ctrl-C while it waits for the server
    finally:
        if currency_client is not None:
            currency_client.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
