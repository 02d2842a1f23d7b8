"""Planar spin-orbit coupling on a Kepler ellipse (Euler ch. 16 P93-P94 with an eccentric orbit).

The body's axis C stays normal to the orbit plane; theta is the angle of its
axis A from the periapsis direction and f the true anomaly of the attracting
mass, so (Euler ch. 16 P91, §825 with s = r(t))

    theta'' = -(3/2) n^2 ((B - A)/C) (a/r)^3 sin 2(theta - f).

Two realisations share the initial conditions: ``rigid_body_system`` is the
full 3-D rigid body (dynamics.make_rigid_body_rhs, quaternion + omega) on a
``KeplerOrbit``; ``planar_rhs`` is the one-angle model above, compiled, for
any number of independent copies at once (state [theta_0, theta'_0, theta_1,
...]), used where many trajectories share one orbit (Lyapunov maps).
Times in days, angles in rad; the orbit has periapsis on the inertial x axis
and mean anomaly 0 at ``t0``.
"""
import math

import numpy as np
from numba import njit

from ..dynamics import point_mass_system
from ..orbits.analytic import KeplerOrbit, eccentric_anomaly
from ..rotations import matrix_from_quat


@njit(cache=True)
def anomaly_and_distance(mean_anomaly, e):
    """(true anomaly f (rad), r/a) for mean anomaly M on an ellipse of eccentricity e."""
    big_e = eccentric_anomaly(mean_anomaly, e)
    f = 2.0 * math.atan2(math.sqrt(1.0 + e) * math.sin(0.5 * big_e), math.sqrt(1.0 - e) * math.cos(0.5 * big_e))
    return f, 1.0 - e * math.cos(big_e)


@njit(cache=True)
def planar_rhs(t, y, p):
    """d/dt [theta_i, theta'_i] for every copy i; p = (n rad/d, e, t0 d, (3/2)(B - A)/C)."""
    n, e, t0, k = p[0], p[1], p[2], p[3]
    f, r = anomaly_and_distance(n * (t - t0), e)
    g = k * n * n / (r * r * r)
    dy = np.empty_like(y)
    for i in range(0, y.shape[0], 2):
        dy[i] = y[i + 1]
        dy[i + 1] = -g * math.sin(2.0 * (y[i] - f))
    return dy


def planar_params(n, e, t0, gamma):
    """The ``p`` array of planar_rhs for mean motion n (rad/d), eccentricity e, periapsis time t0, (B - A)/C."""
    return np.array([n, e, t0, 1.5 * gamma])


def kepler_orbit(gm, a, e, t0):
    """The attracting mass on a Kepler ellipse about the body, periapsis on x at t0 (TDB d)."""
    n = math.sqrt(gm / a**3)
    return KeplerOrbit(("F",), [gm], [a], [e], mean_motion=[n], mean_anomaly=[-n * t0])


def rigid_body_system(moments, orbit, t0, theta0, theta_dot0):
    """Full 3-D rigid body turning about C (= inertial z) at theta_dot0 with A at angle theta0 from periapsis."""
    q0 = np.array([math.cos(theta0 / 2), 0.0, 0.0, math.sin(theta0 / 2)])
    return point_mass_system(moments, orbit, q0, [0.0, 0.0, theta_dot0], t0, "planar spin-orbit")


def theta_from_quaternions(q):
    """Unwrapped angle (rad) of the body's A axis from the inertial x axis, projected on the x-y plane."""
    return np.unwrap(np.array([math.atan2(m[1, 0], m[0, 0]) for m in map(matrix_from_quat, q)]))


def forcing_coefficients(e, k_max=8, samples=4096):
    """Fourier sine coefficients S_k of (a/r)^3 sin(3M - 2f) and the mean H of (a/r)^3 cos(3M - 2f).

    Computed by quadrature over one orbit (exact to rounding for e < 0.5); for
    the 3:2 state S_1 = 1 - 11 e^2 + 959 e^4/48 + O(e^6) and H = 7e/2 - 123 e^3/16
    + O(e^5) (Peale 1972; Margot et al. 2007).  Returns (S (k_max,), H).
    """
    m = 2 * math.pi * np.arange(samples) / samples
    f, r = np.array([anomaly_and_distance(mi, e) for mi in m]).T
    s = np.sin(3 * m - 2 * f) / r**3
    c = np.cos(3 * m - 2 * f) / r**3
    k = np.arange(1, k_max + 1)
    return 2 * np.mean(s * np.sin(np.outer(k, m)), axis=1), float(np.mean(c))
