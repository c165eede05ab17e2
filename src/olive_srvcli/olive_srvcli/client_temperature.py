"""temp_client CELSIUS: ask temp_conversion for Kelvin and Fahrenheit."""

from olive_interfaces.srv import TempConv
from owl_common.client import OneShotClient, UsageError, number_argument, run_client

from olive_srvcli.conversions import check_celsius


class TempClient(OneShotClient):

    def __init__(self):
        super().__init__('temp_client', TempConv, 'temp_conversion')


def request_from_argv(argv: list[str]) -> TempConv.Request:
    temp_c = number_argument(argv, 'a temperature in Celsius')
    problem = check_celsius(temp_c)
    if problem:
        raise UsageError(problem)
    return TempConv.Request(temp_c=temp_c)


def report(node: TempClient, request: TempConv.Request, response: TempConv.Response) -> int:
    node.get_logger().info(
        f'The Temperature of {request.temp_c} Celsius is equal to {response.temp_k} Kelvin '
        f'and {response.temp_f} Fahrenheit')
    return 0


def main(args=None):
    run_client(TempClient, request_from_argv, report, '<celsius>', args)


if __name__ == '__main__':
    main()
