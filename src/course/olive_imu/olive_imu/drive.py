"""How the IMU's angles drive the turtle, kept free of ROS.

REP 103 frames: the IMU's x axis points forward, y left, z up. Tilting it forward (nose down) is a
positive pitch and turning it left a positive yaw; the turtle drives forward for a positive
linear.x and turns left (counter-clockwise) for a positive angular.z. So both factors are
positive: the turtle goes where the IMU leans and turns the way it is turned.
"""


def turtle_velocity(pitch: float, yaw: float, speed_factor: float, turn_factor: float) -> tuple[float, float]:
    """(linear.x in m/s, angular.z in rad/s) for an IMU at pitch and yaw (rad)."""
    return speed_factor * pitch, turn_factor * yaw
