"""Range checks for the random number publisher's parameters, kept free of ROS."""


def check_limits(lower: int, upper: int) -> str | None:
    """Return why lower..upper is not a usable range, or None when it is."""
    if lower > upper:
        return f'lower_limit ({lower}) must not be greater than upper_limit ({upper})'
    return None
