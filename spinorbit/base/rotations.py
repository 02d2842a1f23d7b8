"""Attitude: quaternions, rotation matrices and JPL 3-1-3 Euler angles.

Conventions (docs/DEVELOPING.md):

* A quaternion ``q = (w, x, y, z)`` (scalar first, unit norm) rotates body-frame
  vectors into the inertial frame: ``v_inertial = matrix_from_quat(q) @ v_body``.
* The JPL lunar angles (phi, theta, psi) give the matrix from ICRF to the body
  principal axes, ``M = Rz(psi) Rx(theta) Rz(phi)``, with frame rotations
  ``Rz(a) = [[cos a, sin a, 0], [-sin a, cos a, 0], [0, 0, 1]]``.  So
  ``M = matrix_from_quat(q).T``.
* Kinematics (Euler ch. 15 §809-811 in quaternion form): dq/dt = q * (0, omega_body) / 2.

The functions the compiled kernels call are numba-compiled (when one is first asked for: importing this
module imports no numba, linker.OnDemand) and take/return
plain float64 arrays; the 3-vector and 3x3 helpers (dot3 ... solve3, put) are
written out by element: numba compiles numpy's general array functions
(np.cross, @ through BLAS, np.linalg.solve through LAPACK, np.outer, np.eye,
slice assignment) in seconds each, and every kernel that calls them compiles
them again.  The conversions used only from Python (Euler angles,
quat_from_matrix) are plain numpy, the Euler-angle ones vectorised over leading
axes, so they need no compilation.
"""
import math

import numpy as np

from .linker import OnDemand

compiled = OnDemand(cache=True)     # the kernels' helpers, compiled when first asked for


@compiled
def dot3(a, b):
    """Scalar product a . b of two 3-vectors."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@compiled
def cross3(a, b):
    """Vector product a x b of two 3-vectors."""
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


@compiled
def matvec3(m, v):
    """m @ v for a 3x3 matrix m and a 3-vector v."""
    return np.array([m[0, 0] * v[0] + m[0, 1] * v[1] + m[0, 2] * v[2],
                     m[1, 0] * v[0] + m[1, 1] * v[1] + m[1, 2] * v[2],
                     m[2, 0] * v[0] + m[2, 1] * v[1] + m[2, 2] * v[2]])


@compiled
def mat_t_vec3(m, v):
    """m.T @ v for a 3x3 matrix m and a 3-vector v (e.g. inertial -> body axes with m = R(q))."""
    return np.array([m[0, 0] * v[0] + m[1, 0] * v[1] + m[2, 0] * v[2],
                     m[0, 1] * v[0] + m[1, 1] * v[1] + m[2, 1] * v[2],
                     m[0, 2] * v[0] + m[1, 2] * v[1] + m[2, 2] * v[2]])


@compiled
def diag3(d):
    """The 3x3 diagonal matrix with diagonal d."""
    m = np.zeros((3, 3))
    m[0, 0], m[1, 1], m[2, 2] = d[0], d[1], d[2]
    return m


@compiled
def solve3(m, b):
    """x with m @ x = b for a 3x3 matrix m, by Cramer's rule (cofactors of m).

    Its relative error is a few eps times the condition number of m, as for
    LAPACK's LU: for inertia tensors (condition number C/A, 1.0004 for the Moon)
    both agree with the exact solution to ~1e-16 relative.
    """
    c00 = m[1, 1] * m[2, 2] - m[1, 2] * m[2, 1]
    c01 = m[1, 2] * m[2, 0] - m[1, 0] * m[2, 2]
    c02 = m[1, 0] * m[2, 1] - m[1, 1] * m[2, 0]
    c10 = m[0, 2] * m[2, 1] - m[0, 1] * m[2, 2]
    c11 = m[0, 0] * m[2, 2] - m[0, 2] * m[2, 0]
    c12 = m[0, 1] * m[2, 0] - m[0, 0] * m[2, 1]
    c20 = m[0, 1] * m[1, 2] - m[0, 2] * m[1, 1]
    c21 = m[0, 2] * m[1, 0] - m[0, 0] * m[1, 2]
    c22 = m[0, 0] * m[1, 1] - m[0, 1] * m[1, 0]
    det = m[0, 0] * c00 + m[0, 1] * c01 + m[0, 2] * c02
    return np.array([(c00 * b[0] + c10 * b[1] + c20 * b[2]) / det,
                     (c01 * b[0] + c11 * b[1] + c21 * b[2]) / det,
                     (c02 * b[0] + c12 * b[1] + c22 * b[2]) / det])


@compiled
def put(out, v):
    """out[:] = v for 1-d arrays of equal length, by element (numba's slice assignment
    compiles a shape-error formatter); out may be a view such as y[4:7] or k[s]."""
    if out.shape[0] != v.shape[0]:
        raise ValueError("put: out and v differ in length")
    for i in range(v.shape[0]):
        out[i] = v[i]


@compiled
def quat_multiply(a, b):
    """Hamilton product a * b of two scalar-first quaternions."""
    return np.array([
        a[0] * b[0] - a[1] * b[1] - a[2] * b[2] - a[3] * b[3],
        a[0] * b[1] + a[1] * b[0] + a[2] * b[3] - a[3] * b[2],
        a[0] * b[2] - a[1] * b[3] + a[2] * b[0] + a[3] * b[1],
        a[0] * b[3] + a[1] * b[2] - a[2] * b[1] + a[3] * b[0],
    ])


@compiled
def matrix_from_quat(q):
    """Body-to-inertial rotation matrix of a (not necessarily unit) quaternion."""
    w, x, y, z = q[0], q[1], q[2], q[3]
    s = 2.0 / (w * w + x * x + y * y + z * z)
    return np.array([
        [1 - s * (y * y + z * z), s * (x * y - w * z), s * (x * z + w * y)],
        [s * (x * y + w * z), 1 - s * (x * x + z * z), s * (y * z - w * x)],
        [s * (x * z - w * y), s * (y * z + w * x), 1 - s * (x * x + y * y)],
    ])


def matrices_from_quats(q):
    """Body-to-inertial matrices (..., 3, 3) of quaternions (..., 4), for Python callers: the compiled
    ``matrix_from_quat``'s own source applied to whole arrays.  Python never calls the compiled function itself:
    row by row it is slow, and a compiled function boxed for Python and loaded from numba's cache beside kernels
    compiled in another process can fail to return its array ("'descr' is NULL")."""
    columns = np.moveaxis(np.asarray(q, dtype=float), -1, 0)
    return np.moveaxis(compiled.source("matrix_from_quat")(columns), (0, 1), (-2, -1))


def quat_from_matrix(m):
    """Unit quaternion (w >= 0) of a body-to-inertial rotation matrix (Shepperd's method)."""
    tr = m[0, 0] + m[1, 1] + m[2, 2]
    k, largest = 0, tr                     # the largest of tr, m00, m11, m22 (the first of equals)
    for i in range(3):
        if m[i, i] > largest:
            k, largest = i + 1, m[i, i]
    if k == 0:
        s = 2.0 * math.sqrt(1.0 + tr)
        w, x, y, z = 0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s
    elif k == 1:
        s = 2.0 * math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        w, x, y, z = (m[2, 1] - m[1, 2]) / s, 0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s
    elif k == 2:
        s = 2.0 * math.sqrt(1.0 - m[0, 0] + m[1, 1] - m[2, 2])
        w, x, y, z = (m[0, 2] - m[2, 0]) / s, (m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s
    else:
        s = 2.0 * math.sqrt(1.0 - m[0, 0] - m[1, 1] + m[2, 2])
        w, x, y, z = (m[1, 0] - m[0, 1]) / s, (m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s
    sign = -1.0 if w < 0 else 1.0
    norm = math.sqrt(w ** 2 + x ** 2 + y ** 2 + z ** 2)
    return np.array([sign * w / norm, sign * x / norm, sign * y / norm, sign * z / norm])


@compiled
def quat_rate(q, omega_body):
    """dq/dt for body angular velocity omega_body (rad per time unit)."""
    w, x, y, z = q[0], q[1], q[2], q[3]
    a, b, c = omega_body[0], omega_body[1], omega_body[2]
    return np.array([0.5 * (-x * a - y * b - z * c), 0.5 * (w * a + y * c - z * b),     # q * (0, omega) / 2
                     0.5 * (w * b - x * c + z * a), 0.5 * (w * c + x * b - y * a)])


def frame_rotation(axis, angle):
    """The matrix [angle]_axis (axis 1, 2 or 3; rad) taking a vector's coordinates to the frame turned by
    ``angle`` about that axis (SPICE's ``rotate``; Rz below)."""
    c, s = np.cos(angle), np.sin(angle)
    i, j = [(1, 2), (2, 0), (0, 1)][axis - 1]
    m = np.eye(3)
    m[i, i], m[i, j], m[j, i], m[j, j] = c, s, -s, c
    return m


def matrix_from_euler313(phi, theta, psi):
    """ICRF-to-body matrix M = Rz(psi) Rx(theta) Rz(phi) (JPL lunar convention), rad.

    Angles of shape (...) give matrices (..., 3, 3).
    """
    cf, sf = np.cos(phi), np.sin(phi)
    ct, st = np.cos(theta), np.sin(theta)
    cp, sp = np.cos(psi), np.sin(psi)
    rows = ([cp * cf - sp * ct * sf, cp * sf + sp * ct * cf, sp * st],
            [-sp * cf - cp * ct * sf, -sp * sf + cp * ct * cf, cp * st],
            [st * sf, -st * cf, ct])
    return np.stack([np.stack(np.broadcast_arrays(*row), axis=-1) for row in rows], axis=-2)


def euler313_from_matrix(m):
    """(phi, theta, psi) in rad of ICRF-to-body matrices (..., 3, 3); phi, psi in [0, 2 pi).

    At the gimbal singularity (sin theta below 1e-15) only phi + psi is defined;
    phi is set to 0 there.
    """
    m = np.asarray(m, dtype=float)
    st = np.hypot(m[..., 2, 0], m[..., 2, 1])
    theta = np.arctan2(st, m[..., 2, 2])
    regular = st > 1e-15
    phi = np.where(regular, np.arctan2(m[..., 2, 0], -m[..., 2, 1]), 0.0)
    psi_singular = np.arctan2(np.where(m[..., 2, 2] > 0, m[..., 0, 1], -m[..., 0, 1]), m[..., 0, 0])
    psi = np.where(regular, np.arctan2(m[..., 0, 2], m[..., 1, 2]), psi_singular)
    two_pi = 2.0 * np.pi
    return np.stack([phi % two_pi, theta, psi % two_pi], axis=-1)


def omega_body_from_euler313_rates(angles, rates):
    """Body angular velocity from 3-1-3 angles and their rates (JPL convention), shapes (..., 3)."""
    angles, rates = np.asarray(angles, dtype=float), np.asarray(rates, dtype=float)
    theta, psi = angles[..., 1], angles[..., 2]
    dphi, dtheta, dpsi = rates[..., 0], rates[..., 1], rates[..., 2]
    st, ct, sp, cp = np.sin(theta), np.cos(theta), np.sin(psi), np.cos(psi)
    return np.stack([dphi * st * sp + dtheta * cp, dphi * st * cp - dtheta * sp, dphi * ct + dpsi], axis=-1)


def quat_from_rotation_vector(w):
    """Unit quaternion(s) (..., 4) of rotation vector(s) w (..., 3): angle |w| (rad) about w/|w|."""
    w = np.asarray(w, dtype=float)
    angle = np.linalg.norm(w, axis=-1, keepdims=True)
    axis = np.divide(w, angle, out=np.zeros_like(w), where=angle > 0)
    return np.concatenate([np.cos(angle / 2), np.sin(angle / 2) * axis], axis=-1)


def quat_from_euler313(phi, theta, psi):
    """Body-to-inertial quaternion of JPL 3-1-3 angles (rad)."""
    return quat_from_matrix(matrix_from_euler313(phi, theta, psi).T)


def euler313_from_quat(q):
    """JPL 3-1-3 angles (rad) of a body-to-inertial quaternion."""
    return euler313_from_matrix(np.swapaxes(matrices_from_quats(q), -1, -2))


def quat_angle(q_a, q_b):
    """Rotation angle (rad) between attitudes q_a and q_b, shape (..., 4); accurate near 0.

    2 atan2(|vec(conj(q_a) q_b)|, |scalar|): unlike 2 arccos|q_a.q_b| it
    resolves differences far below 1e-8 rad.
    """
    q_a, q_b = np.asarray(q_a, dtype=float), np.asarray(q_b, dtype=float)
    w = np.sum(q_a * q_b, axis=-1)
    v = (q_a[..., :1] * q_b[..., 1:] - q_b[..., :1] * q_a[..., 1:]
         - np.cross(q_a[..., 1:], q_b[..., 1:]))
    return 2.0 * np.arctan2(np.linalg.norm(v, axis=-1), np.abs(w))


def vector_angle(a, b):
    """Angle (rad) between vectors a and b, shape (..., 3); atan2(|a x b|, a.b), accurate near 0 and pi."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=-1), np.sum(a * b, axis=-1))


__getattr__ = compiled.hide(globals())
