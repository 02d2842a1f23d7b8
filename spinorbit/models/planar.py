"""The planar spin-orbit problem: one angle of a body whose axis C stays normal to its orbit's plane.

theta is the angle of the axis A from the periapsis direction and f the true anomaly of the attracting mass, so
(Euler ch. 16 P91, §825 with s = r(t); the stress scenes' Kepler ellipse)

    theta'' = -(3/2) n^2 ((B - A)/C) (a/r)^3 sin 2(theta - f).

The right-hand side integrates any number of independent copies at once (state [theta_0, theta'_0, theta_1, ...]).
Times in days, angles in rad; mean anomaly n (t - t0).
"""
import math

import numpy as np

from ..base.layout import Layout
from ..base.linker import cached
from ..orbits.analytic import eccentric_anomaly
from .ode import Ode


@cached(nogil=True)
def anomaly_and_distance(mean_anomaly, e):
    """(true anomaly f (rad), r/a) for mean anomaly M on an ellipse of eccentricity e."""
    big_e = eccentric_anomaly(mean_anomaly, e)
    f = 2.0 * math.atan2(math.sqrt(1.0 + e) * math.sin(0.5 * big_e), math.sqrt(1.0 - e) * math.cos(0.5 * big_e))
    return f, 1.0 - e * math.cos(big_e)


@cached(nogil=True)
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


def planar_ode(p, t0, theta, rate):
    """One copy of the planar equation as the integrator door runs it, from (theta, theta') at t0."""
    layout = Layout([("body.theta", 1, "vector", "rad"), ("body.rate", 1, "vector", "rad/d")])
    return Ode(planar_rhs, p, float(t0), np.array([theta, rate], dtype=float), layout, name="planar")
