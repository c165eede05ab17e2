"""The robot view: a 3D model of the Owl Kit in a browser."""
