"""The QoS a subscriber takes to hear every publisher of a topic (ros2 topic echo's and rqt's)."""

from owl_common.graph import matching_policies


def endpoint(reliability: str, durability: str) -> dict[str, str]:
    return {'reliability': reliability, 'durability': durability}


def test_reliable_and_durable_only_when_every_publisher_is():
    assert matching_policies([endpoint('RELIABLE', 'TRANSIENT_LOCAL')]) == ('RELIABLE', 'TRANSIENT_LOCAL')
    mixed = [endpoint('RELIABLE', 'TRANSIENT_LOCAL'), endpoint('BEST_EFFORT', 'VOLATILE')]
    assert matching_policies(mixed) == ('BEST_EFFORT', 'VOLATILE')
    assert matching_policies([endpoint('RELIABLE', 'VOLATILE')] * 2) == ('RELIABLE', 'VOLATILE')
    assert matching_policies([]) == ('BEST_EFFORT', 'VOLATILE')  # whatever publisher comes later
