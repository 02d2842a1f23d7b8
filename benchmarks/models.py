"""The benchmark model written three ways: spinorbit's numba rhs, a pure-NumPy rhs, heyoka expressions.

Rigid body (quaternion body -> inertial, body omega) under the point-mass torque
of Euler ch. 16 P91 (§815), the mass on a uniform inclined circle:
r(t) = R (cos nt, sin nt cos i, sin nt sin i).  Time unit: days.
"""
import math

import numpy as np

MOMENTS = np.array([0.8, 1.0, 1.3])
GM, RADIUS, RATE, INCL = 0.5, 1.0, 1.0, 0.3
Y0 = np.array([0.9, 0.1, 0.3, 0.2, 0.3, -0.4, 1.2])
Y0[:4] /= np.linalg.norm(Y0[:4])


def numba_system(gm=GM, moments=MOMENTS, y0=Y0):
    """spinorbit's System for the model (compiled rhs and torque)."""
    from spinorbit.models.assemblies.idealised import under_point_masses
    from spinorbit.orbits.analytic import CircularOrbits

    orbit = CircularOrbits(("m",), gm=[gm], radius=[RADIUS], rate=[RATE], inclination=[INCL])
    return under_point_masses(moments, orbit, y0[:4], y0[4:7])


def numpy_rhs(t, y, moments=MOMENTS, gm=GM):
    """The right-hand side as a user would write it with NumPy."""
    q, w = y[:4], y[4:7]
    a = RATE * t
    r = RADIUS * np.array([math.cos(a), math.sin(a) * math.cos(INCL), math.sin(a) * math.sin(INCL)])
    q0, q1, q2, q3 = q / np.linalg.norm(q)
    rot = np.array([[1 - 2 * (q2**2 + q3**2), 2 * (q1 * q2 - q0 * q3), 2 * (q1 * q3 + q0 * q2)],
                    [2 * (q1 * q2 + q0 * q3), 1 - 2 * (q1**2 + q3**2), 2 * (q2 * q3 - q0 * q1)],
                    [2 * (q1 * q3 - q0 * q2), 2 * (q2 * q3 + q0 * q1), 1 - 2 * (q1**2 + q2**2)]])
    rb = rot.T @ r
    torque = 3 * gm / np.linalg.norm(rb) ** 5 * np.cross(rb, moments * rb)
    w_dot = (torque - np.cross(w, moments * w)) / moments
    q_dot = 0.5 * np.array([-q1 * w[0] - q2 * w[1] - q3 * w[2], q0 * w[0] + q2 * w[2] - q3 * w[1],
                            q0 * w[1] - q1 * w[2] + q3 * w[0], q0 * w[2] + q1 * w[1] - q2 * w[0]])
    return np.concatenate([q_dot, w_dot])


def heyoka_equations(gm=GM, moments=MOMENTS):
    """(variables, right-hand sides) of the model as heyoka expressions (time = heyoka.time)."""
    import heyoka as hy

    q0, q1, q2, q3, wx, wy, wz = hy.make_vars("q0", "q1", "q2", "q3", "wx", "wy", "wz")
    a, b, c = (float(m) for m in moments)
    ang = RATE * hy.time
    rx, ry, rz = RADIUS * hy.cos(ang), RADIUS * math.cos(INCL) * hy.sin(ang), RADIUS * math.sin(INCL) * hy.sin(ang)
    # r_body = R(q)^T r (unit quaternion)
    bx = (1 - 2 * (q2**2 + q3**2)) * rx + 2 * (q1 * q2 + q0 * q3) * ry + 2 * (q1 * q3 - q0 * q2) * rz
    by = 2 * (q1 * q2 - q0 * q3) * rx + (1 - 2 * (q1**2 + q3**2)) * ry + 2 * (q2 * q3 + q0 * q1) * rz
    bz = 2 * (q1 * q3 + q0 * q2) * rx + 2 * (q2 * q3 - q0 * q1) * ry + (1 - 2 * (q1**2 + q2**2)) * rz
    k = 3 * gm * (bx**2 + by**2 + bz**2) ** -2.5
    rhs = [0.5 * (-q1 * wx - q2 * wy - q3 * wz), 0.5 * (q0 * wx + q2 * wz - q3 * wy),
           0.5 * (q0 * wy - q1 * wz + q3 * wx), 0.5 * (q0 * wz + q1 * wy - q2 * wx),
           (k * (c - b) * by * bz - (c - b) * wy * wz) / a,
           (k * (a - c) * bz * bx - (a - c) * wz * wx) / b,
           (k * (b - a) * bx * by - (b - a) * wx * wy) / c]
    return [q0, q1, q2, q3, wx, wy, wz], rhs


def numpy_free_rhs(t, y, moments):
    """Torque-free rigid body (Euler ch. 15 §808) as a user would write it with NumPy."""
    q, w = y[:4], y[4:7]
    w_dot = -np.cross(w, moments * w) / moments
    q_dot = 0.5 * np.array([-q[1] * w[0] - q[2] * w[1] - q[3] * w[2], q[0] * w[0] + q[2] * w[2] - q[3] * w[1],
                            q[0] * w[1] - q[1] * w[2] + q[3] * w[0], q[0] * w[2] + q[1] * w[1] - q[2] * w[0]])
    return np.concatenate([q_dot, w_dot])


def heyoka_free_equations(moments):
    """heyoka (variable, rhs) pairs of the torque-free body."""
    import heyoka as hy

    q0, q1, q2, q3, wx, wy, wz = hy.make_vars("q0", "q1", "q2", "q3", "wx", "wy", "wz")
    a, b, c = (float(m) for m in moments)
    rhs = [0.5 * (-q1 * wx - q2 * wy - q3 * wz), 0.5 * (q0 * wx + q2 * wz - q3 * wy),
           0.5 * (q0 * wy - q1 * wz + q3 * wx), 0.5 * (q0 * wz + q1 * wy - q2 * wx),
           -(c - b) * wy * wz / a, -(a - c) * wz * wx / b, -(b - a) * wx * wy / c]
    return list(zip([q0, q1, q2, q3, wx, wy, wz], rhs))
