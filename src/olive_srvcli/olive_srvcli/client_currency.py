"""currency_client EUROS: ask currency_conversion for dollars, pounds and Swiss francs."""

from olive_interfaces.srv import CurrencyConv
from owl_common.client import OneShotClient, UsageError, number_argument, run_client


class CurrencyClient(OneShotClient):

    def __init__(self):
        super().__init__('currency_client', CurrencyConv, 'currency_conversion')


def request_from_argv(argv: list[str]) -> CurrencyConv.Request:
    euros = number_argument(argv, 'an amount in euros')
    if euros < 0:
        raise UsageError(f'the amount must not be negative, got {euros}')
    return CurrencyConv.Request(euros=euros)


def report(node: CurrencyClient, request: CurrencyConv.Request,
           response: CurrencyConv.Response) -> int:
    if not response.success:
        node.get_logger().error(f'The server refused: {response.message}')
        return 1
    node.get_logger().info(
        f'{request.euros} Euros are {response.dollars} US dollars, {response.pounds} British '
        f'pounds and {response.swiss_francs} Swiss francs')
    return 0


def main(args=None):
    run_client(CurrencyClient, request_from_argv, report, '<euros>', args)


if __name__ == '__main__':
    main()
