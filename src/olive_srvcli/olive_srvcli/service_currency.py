"""currency_server: convert euros into US dollars, British pounds and Swiss francs.

The exchange rates are parameters (units per euro), changeable at runtime.
"""

from olive_interfaces.srv import CurrencyConv
from owl_common.run import spin_node
from rcl_interfaces.msg import FloatingPointRange, ParameterDescriptor
from rclpy.node import Node

from olive_srvcli.conversions import convert_euros

# Units per euro; reference rates of late 2025, close enough for an exercise.
DEFAULT_RATES = {'usd_per_eur': 1.16, 'gbp_per_eur': 0.88, 'chf_per_eur': 0.93}
RATE_RANGE = FloatingPointRange(from_value=0.0001, to_value=10000.0)


class CurrencyService(Node):

    def __init__(self):
        super().__init__('currency_service')
        for name, default in DEFAULT_RATES.items():
            currency = name.split('_')[0].upper()
            self.declare_parameter(name, default, ParameterDescriptor(
                description=f'{currency} for one euro.', floating_point_range=[RATE_RANGE]))
        self.srv = self.create_service(CurrencyConv, 'currency_conversion', self.convert_callback)

    def convert_callback(self, request, response):
        self.get_logger().info(f'Incoming request: {request.euros} euros')
        rates = {name: self.get_parameter(name).value for name in DEFAULT_RATES}
        outcome = convert_euros(request.euros, rates)
        response.success = outcome.ok
        if not outcome.ok:
            response.message = outcome.error
            self.get_logger().warn(f'Refusing request: {outcome.error}')
            return response
        response.dollars = outcome.value['usd_per_eur']
        response.pounds = outcome.value['gbp_per_eur']
        response.swiss_francs = outcome.value['chf_per_eur']
        return response


def main(args=None):
    spin_node(CurrencyService, args)


if __name__ == '__main__':
    main()
