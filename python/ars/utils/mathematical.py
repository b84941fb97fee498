"""Vector arithmetic on 3-tuples, as the original ARS programs use it
(``import ars.utils.mathematical as mut``). Vectors are any sequences; results are
tuples of floats. Sums are taken left to right, so results are the same to the bit as
the original's."""

from math import acos, cos, pi, sin, sqrt  # noqa: F401  (re-exported, as the original did)


def radians_to_degrees(radians_):
    return radians_ * 180.0 / pi


def degrees_to_radians(degrees_):
    return degrees_ * pi / 180.0


def vec3_radians_to_degrees(vector_):
    return tuple(radians_to_degrees(x) for x in vector_)


def vec3_degrees_to_radians(vector_):
    return tuple(degrees_to_radians(x) for x in vector_)


def sign(x):
    """``1.0`` for a positive ``x``, else ``-1.0`` (also for zero)."""
    return 1.0 if x > 0.0 else -1.0


def length2(v):
    return sqrt(v[0] ** 2 + v[1] ** 2)


def length3(v):
    return sqrt(v[0] ** 2 + v[1] ** 2 + v[2] ** 2)


def neg3(v):
    return (-v[0], -v[1], -v[2])


def add3(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def sub3(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def mult_by_scalar3(v, s):
    return (v[0] * s, v[1] * s, v[2] * s)


def div_by_scalar3(v, s):
    return (v[0] / s, v[1] / s, v[2] / s)


def dist3(a, b):
    return length3(sub3(a, b))


def dot_product(a, b):
    total = 0
    for x, y in zip(a, b):
        total += x * y
    return total


def dot_product3(a, b):
    return dot_product(a, b)


def unitize(v):
    """``v`` scaled to unit length (zeros for a zero vector)."""
    norm = sqrt(dot_product(v, v))
    if norm > 0.0:
        return tuple(x / norm for x in v)
    return (0.0, 0.0, 0.0)


def norm3(v):
    return unitize(v)


def cross_product(a, b):
    return (
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    )


def project3(v, unit):
    return mult_by_scalar3(v, dot_product3(norm3(v), unit))


def acos_dot3(a, b):
    x = dot_product3(a, b)
    if x < -1.0:
        return pi
    if x > 1.0:
        return 0.0
    return acos(x)


def rotate3(rot, v):
    """The row-major 3×3 matrix ``rot`` (9 numbers) times ``v``."""
    return (
        v[0] * rot[0] + v[1] * rot[1] + v[2] * rot[2],
        v[0] * rot[3] + v[1] * rot[4] + v[2] * rot[5],
        v[0] * rot[6] + v[1] * rot[7] + v[2] * rot[8],
    )


def transpose3(m):
    return (m[0], m[3], m[6], m[1], m[4], m[7], m[2], m[5], m[8])


def z_axis(rot):
    """The third column of a row-major rotation (its local Z in the world)."""
    return (rot[2], rot[5], rot[8])


def matrix_as_3x3_tuples(m9):
    if isinstance(m9, tuple) and len(m9) == 9:
        return (m9[0:3], m9[3:6], m9[6:9])
    return None


def matrix_as_tuple(matrix):
    return tuple(tuple(float(x) for x in row) for row in matrix)


def matrix_multiply(a, b):
    import numpy as np  # here, not above: most programs never multiply matrices

    return matrix_as_tuple(np.dot(np.array(a), np.array(b)))


def np_matrix_to_tuple(array_):
    return matrix_as_tuple(array_)


def calc_acceleration(time_step, vel0, vel1):
    """``(vel1 - vel0) / time_step``, or ``None`` if either velocity is ``None``."""
    if vel0 is None or vel1 is None:
        return None
    return div_by_scalar3(sub3(vel1, vel0), time_step)


def vector_matrix_vector(v, m):
    """``vᵀ M v``."""
    import numpy as np  # here, not above: most programs never need it

    a = np.array(v)
    return np.dot(np.dot(a.T, np.array(m)), a)
