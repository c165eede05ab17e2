"""currency_server: convert euros into US dollars, British pounds and Swiss francs.

The exchange rates are parameters (units per euro), changeable at runtime.
"""

import signal
import sys

import rclpy
from olive_interfaces.srv import CurrencyConv
from rcl_interfaces.msg import FloatingPointRange, ParameterDescriptor
from rclpy.exceptions import ParameterException
from rclpy.node import Node

from olive_srvcli.conversions import convert_euros

# Units per euro; reference rates of late 2025, close enough for an exercise.
DEFAULT_RATES = {'usd_per_eur': 1.16, 'gbp_per_eur': 0.88, 'chf_per_eur': 0.93}
RATE_RANGE = FloatingPointRange(from_value=0.0001, to_value=10000.0)


class CurrencyService(Node):

    def __init__(self) -> None:
        super().__init__('currency_service')
        for name, default in DEFAULT_RATES.items():
            currency = name.split('_')[0].upper()
            self.declare_parameter(name, default, ParameterDescriptor(
                description=f'{currency} for one euro.', floating_point_range=[RATE_RANGE]))
        self.srv = self.create_service(CurrencyConv, 'currency_conversion', self.convert_callback)

    def convert_callback(self, request: CurrencyConv.Request,
                         response: CurrencyConv.Response) -> CurrencyConv.Response:
        self.get_logger().info(f'Incoming request: {request.euros} euros')
        rates = {name: self.get_parameter(name).value for name in DEFAULT_RATES}
        outcome = convert_euros(request.euros, rates)
        response.success = outcome.ok
        if outcome.value is None:  # not ok: error says why
            response.message = outcome.error
            self.get_logger().warn(f'Refusing request: {outcome.error}')
            return response
        response.dollars = outcome.value['usd_per_eur']
        response.pounds = outcome.value['gbp_per_eur']
        response.swiss_francs = outcome.value['chf_per_eur']
        return response


def main(args: list[str] | None = None) -> None:
    rclpy.init(args=args)
    currency_service = None
    try:
        currency_service = CurrencyService()
        rclpy.spin(currency_service)
    except KeyboardInterrupt:
        pass  # Ctrl-C is how the course stops a node
    except (ParameterException, ValueError) as error:
        if currency_service is not None:
            raise
        print(f'currency_server: error: {error}', file=sys.stderr)  # a bad --ros-args parameter
        sys.exit(2)
    finally:
        signal.signal(signal.SIGINT, signal.SIG_IGN)  # a second Ctrl-C must not stop the clean-up
        if currency_service is not None:
            currency_service.destroy_node()
        rclpy.shutdown()


if __name__ == '__main__':
    main()
