"""Rotations of the original ARS API: row-major 3×3 matrices as 9-tuples."""

from math import cos, sin


def calc_rotation_matrix(axis, angle):
    """The rotation by ``angle`` (rad) about ``axis`` (taken as given, not normalised),
    by Rodrigues' formula, as a row-major 9-tuple (the original's arithmetic, to the
    bit)."""
    x, y, z = axis
    c, s = cos(angle), sin(angle)
    t = 1.0 - c
    return (
        t * x**2 + c,
        t * x * y - s * z,
        t * x * z + s * y,
        t * x * y + s * z,
        t * y**2 + c,
        t * y * z - s * x,
        t * x * z - s * y,
        t * y * z + s * x,
        t * z**2 + c,
    )
