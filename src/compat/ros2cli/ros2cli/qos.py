"""QoS from the command line: preset profiles and policy overrides by their short names."""

import argparse
from typing import TYPE_CHECKING

if TYPE_CHECKING:  # rclpy is imported where it is used: `ros2 -h` imports this module
    from rclpy.qos import QoSProfile

PROFILES = ('system_default', 'sensor_data', 'services_default', 'parameters', 'parameter_events',
            'action_status_default', 'default', 'unknown', 'best_available')
HISTORY = ('system_default', 'keep_last', 'keep_all', 'unknown')
RELIABILITY = ('system_default', 'reliable', 'best_effort', 'unknown', 'best_available')
DURABILITY = ('system_default', 'transient_local', 'volatile', 'unknown', 'best_available')
LIVELINESS = ('system_default', 'automatic', 'manual_by_topic', 'unknown', 'best_available')
OVERRIDES = ('qos_depth', 'qos_history', 'qos_reliability', 'qos_durability', 'qos_liveliness',
             'qos_liveliness_lease_duration_seconds')


def add_qos_arguments(parser: argparse.ArgumentParser, entity: str, default_profile: str) -> None:
    """Add --qos-profile (default: default_profile) and the policy overrides; entity is the help's verb."""
    parser.add_argument(
        '--qos-profile', choices=PROFILES, default=default_profile,
        help=f'Quality of service preset profile to {entity} with (default: {default_profile})')
    parser.add_argument('--qos-depth', metavar='N', type=int, default=-1,
                        help=f'Queue size setting to {entity} with (overrides depth value of --qos-profile)')
    parser.add_argument('--qos-history', choices=HISTORY,
                        help=f'History of samples setting to {entity} with (overrides history value '
                             'of --qos-profile)')
    parser.add_argument('--qos-reliability', choices=RELIABILITY,
                        help=f'Quality of service reliability setting to {entity} with (overrides '
                             'reliability value of --qos-profile)')
    parser.add_argument('--qos-durability', choices=DURABILITY,
                        help=f'Quality of service durability setting to {entity} with (overrides '
                             'durability value of --qos-profile)')
    parser.add_argument('--qos-liveliness', choices=LIVELINESS,
                        help=f'Quality of service liveliness setting to {entity} with (overrides '
                             'liveliness value of --qos-profile)')
    parser.add_argument('--qos-liveliness-lease-duration-seconds', type=float,
                        help=f'Quality of service liveliness lease duration setting to {entity} '
                             'with (overrides liveliness lease duration value of --qos-profile)')


def has_overrides(args: argparse.Namespace) -> bool:
    """True when any policy was given explicitly (a depth below 0 means 'not given')."""
    return any(
        (getattr(args, name, None) is not None and not (name == 'qos_depth' and args.qos_depth < 0))
        for name in OVERRIDES)


def profile_from_args(args: argparse.Namespace) -> 'QoSProfile':
    """The --qos-profile preset with every explicitly given policy applied."""
    # Lazy: rclpy is slow to import, and `ros2 topic -h` imports this module (through the verbs).
    from rclpy.duration import Duration
    from rclpy.qos import (
        QoSDurabilityPolicy,
        QoSHistoryPolicy,
        QoSLivelinessPolicy,
        QoSPresetProfiles,
        QoSProfile,
        QoSReliabilityPolicy,
    )

    base = QoSPresetProfiles.get_from_short_key(args.qos_profile)
    profile = QoSProfile(history=base.history, depth=base.depth, reliability=base.reliability,
                         durability=base.durability, lifespan=base.lifespan, deadline=base.deadline,
                         liveliness=base.liveliness,
                         liveliness_lease_duration=base.liveliness_lease_duration)
    if args.qos_history is not None:
        profile.history = QoSHistoryPolicy.get_from_short_key(args.qos_history)
    if args.qos_reliability is not None:
        profile.reliability = QoSReliabilityPolicy.get_from_short_key(args.qos_reliability)
    if args.qos_durability is not None:
        profile.durability = QoSDurabilityPolicy.get_from_short_key(args.qos_durability)
    if getattr(args, 'qos_liveliness', None) is not None:
        profile.liveliness = QoSLivelinessPolicy.get_from_short_key(args.qos_liveliness)
    if getattr(args, 'qos_liveliness_lease_duration_seconds', None) is not None:
        profile.liveliness_lease_duration = Duration(
            nanoseconds=int(args.qos_liveliness_lease_duration_seconds * 1e9))
    if args.qos_depth >= 0:
        profile.depth = args.qos_depth
    elif profile.durability == QoSDurabilityPolicy.TRANSIENT_LOCAL and profile.depth == 0:
        profile.depth = 1
    return profile
