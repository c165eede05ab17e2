"""Helpers of the simulator, the compat tools, the tests, the demo and the benchmarks.

Running a node until Ctrl-C with a clean exit, periodic threads, starting processes in a private ROS
domain.
"""
