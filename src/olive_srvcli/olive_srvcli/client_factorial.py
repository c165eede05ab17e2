"""factorial_client N: ask the factorial service for N!."""

from olive_interfaces.srv import Factorial
from owl_common.client import OneShotClient, UsageError, number_argument, run_client


class FactorialClient(OneShotClient):

    def __init__(self):
        super().__init__('factorial_client', Factorial, 'factorial')


def request_from_argv(argv: list[str]) -> Factorial.Request:
    # Range checks are the server's job: it answers success=false with the reason.
    n = number_argument(argv, 'an integer', kind=int)
    if not -2**63 <= n < 2**63:
        raise UsageError(f'{n} does not fit the 64-bit integer of the request')
    return Factorial.Request(n=n)


def report(node: FactorialClient, request: Factorial.Request, response: Factorial.Response) -> int:
    if not response.success:
        node.get_logger().error(f'The server refused: {response.message}')
        return 1
    node.get_logger().info(f'The factorial of {request.n} is {response.factorial}')
    return 0


def main(args=None):
    run_client(FactorialClient, request_from_argv, report, '<n>', args)


if __name__ == '__main__':
    main()
