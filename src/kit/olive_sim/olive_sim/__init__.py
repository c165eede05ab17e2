"""Simulated Olive modules of the Owl Kit (IMU, servo, camera) with the real modules' ROS interfaces."""
