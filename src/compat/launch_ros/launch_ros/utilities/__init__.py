"""Helpers of launch_ros that other launch code imports (upstream's launch_ros.utilities)."""

from launch_ros.utilities.evaluate_parameters import evaluate_parameters
from launch_ros.utilities.namespace_utils import (
    is_namespace_absolute,
    is_root_namespace,
    make_namespace_absolute,
    prefix_namespace,
)
from launch_ros.utilities.normalize_parameters import normalize_parameters
from launch_ros.utilities.normalize_remap_rule import normalize_remap_rule, normalize_remap_rules
from launch_ros.utilities.to_parameters_list import to_parameters_list
from launch_ros.utilities.track_node_names import add_node_name, get_node_name_count

# Upstream's list also names evaluate_parameters_dict and normalize_parameters_dict, which it does not
# define (so its `import *` fails); the functions are evaluate_parameter_dict and normalize_parameter_dict
# in their modules.
__all__ = [
    'add_node_name', 'evaluate_parameters', 'get_node_name_count', 'is_namespace_absolute',
    'is_root_namespace', 'make_namespace_absolute', 'normalize_parameters', 'normalize_remap_rule',
    'normalize_remap_rules', 'prefix_namespace', 'to_parameters_list',
]
