"""Analytic orbits: Euler's uniform circle (ch. 16 P93, P96) and the Kepler ellipse (P94).

Times are in the scene's time unit (days for real scenes); the circle lies in
the inertial x-y plane unless an inclination is given (tilted about x).
"""
import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from ..base.errors import InputError


def _per_body(n, *values):
    """Each value as a float array of one entry per body (None -> zeros)."""
    return [np.zeros(n) if v is None else np.asarray(v, dtype=float).reshape(n) for v in values]


@njit(cache=True)
def _circle_positions(t, data):
    """data = (radius (n,), rate (n,), phase (n,), inclination (n,)) -> (n, 3)."""
    radius, rate, phase, incl = data
    out = np.empty((radius.shape[0], 3))
    for i in range(radius.shape[0]):
        a = rate[i] * t + phase[i]
        x, y = radius[i] * math.cos(a), radius[i] * math.sin(a)
        out[i, 0] = x
        out[i, 1] = y * math.cos(incl[i])
        out[i, 2] = y * math.sin(incl[i])
    return out


@dataclass
class CircularOrbits:
    """Point masses on uniform circles about the body (Euler's hypothesis, §825, §844).

    radius in km (or scene length unit), rate in rad per time unit (Euler's delta),
    phase in rad at t = 0, inclination in rad of the orbit plane to the x-y plane.
    """

    names: tuple
    gm: np.ndarray
    radius: np.ndarray
    rate: np.ndarray
    phase: np.ndarray = None
    inclination: np.ndarray = None
    span: tuple = (-math.inf, math.inf)
    data: tuple = field(init=False)

    def __post_init__(self):
        n = len(self.names)
        self.gm, self.radius, self.rate, self.phase, self.inclination = _per_body(
            n, self.gm, self.radius, self.rate, self.phase, self.inclination)
        if np.any(self.radius <= 0):
            raise InputError("radius", self.radius.tolist(), "positive distances")
        self.data = (self.radius, self.rate, self.phase, self.inclination)

    kernel = staticmethod(_circle_positions)

    def positions(self, t):
        return np.array([_circle_positions(ti, self.data) for ti in np.atleast_1d(t)])


@njit(cache=True)
def eccentric_anomaly(mean_anomaly, e):
    """Solve Kepler's equation E - e sin E = M by Newton's method (0 <= e < 1), rad."""
    m = mean_anomaly - 2.0 * math.pi * round(mean_anomaly / (2.0 * math.pi))
    big_e = m + e * math.sin(m) if e < 0.8 else math.copysign(math.pi, m)
    for _ in range(50):
        step = (big_e - e * math.sin(big_e) - m) / (1.0 - e * math.cos(big_e))
        big_e -= step
        if abs(step) < 1e-15:
            break
    return big_e


@njit(cache=True)
def _kepler_positions(t, data):
    """data = (a, e, n, M0, P (n, 3), Q (n, 3)) -> (n, 3): r = a(cos E - e) P + b sin E Q."""
    a, e, rate, m0, p, q = data
    out = np.empty((a.shape[0], 3))
    for i in range(a.shape[0]):
        big_e = eccentric_anomaly(m0[i] + rate[i] * t, e[i])
        x = a[i] * (math.cos(big_e) - e[i])
        y = a[i] * math.sqrt(1.0 - e[i] * e[i]) * math.sin(big_e)
        for j in range(3):
            out[i, j] = x * p[i, j] + y * q[i, j]
    return out


@dataclass
class KeplerOrbit:
    """Point masses on fixed Kepler ellipses about the body (two-body motion; Euler ch. 16 P94).

    a in km (or scene length unit), e in [0, 1), mean_motion n in rad per time
    unit (None: sqrt(gm / a^3), right when the attracting mass dominates, e.g. the
    Sun about Mercury), mean_anomaly at t = 0, and the orientation angles (rad)
    periapsis (argument of periapsis), inclination and node, as r = Rz(node)
    Rx(inclination) Rz(periapsis) applied to the ellipse in its own plane.
    With node = 0 the plane is tilted about x, as in :class:`CircularOrbits`.
    """

    names: tuple
    gm: np.ndarray
    a: np.ndarray
    e: np.ndarray
    mean_motion: np.ndarray = None
    mean_anomaly: np.ndarray = None
    periapsis: np.ndarray = None
    inclination: np.ndarray = None
    node: np.ndarray = None
    span: tuple = (-math.inf, math.inf)
    data: tuple = field(init=False)

    def __post_init__(self):
        n = len(self.names)
        self.gm, self.a, self.e = _per_body(n, self.gm, self.a, self.e)
        if np.any(self.a <= 0):
            raise InputError("a", self.a.tolist(), "positive semi-major axes")
        if np.any((self.e < 0) | (self.e >= 1)):
            raise InputError("e", self.e.tolist(), "eccentricities in [0, 1)")
        if self.mean_motion is None:
            self.mean_motion = np.sqrt(self.gm / self.a**3)
        self.mean_motion, self.mean_anomaly, self.periapsis, self.inclination, self.node = _per_body(
            n, self.mean_motion, self.mean_anomaly, self.periapsis, self.inclination, self.node)
        cw, sw = np.cos(self.periapsis), np.sin(self.periapsis)
        ci, si = np.cos(self.inclination), np.sin(self.inclination)
        co, so = np.cos(self.node), np.sin(self.node)
        p = np.stack([co * cw - so * ci * sw, so * cw + co * ci * sw, si * sw], axis=1)
        q = np.stack([-co * sw - so * ci * cw, -so * sw + co * ci * cw, si * cw], axis=1)
        self.data = (self.a, self.e, self.mean_motion, self.mean_anomaly, p, q)

    kernel = staticmethod(_kepler_positions)

    def positions(self, t):
        return np.array([_kepler_positions(ti, self.data) for ti in np.atleast_1d(t)])


@njit(cache=True)
def _uneven_circle_positions(t, data):
    """data = (f, delta, alpha, beta, a_freq, phase), each (n,) -> (n, 3) in the x-y plane."""
    f, delta, alpha, beta, a_freq, phase = data
    out = np.zeros((f.shape[0], 3))
    for i in range(f.shape[0]):
        angle = delta[i] * t + alpha[i] * math.sin(a_freq[i] * t) + phase[i]
        s = f[i] * (1.0 + beta[i] * math.cos(a_freq[i] * t)) ** (-1.0 / 3.0)
        out[i, 0] = s * math.cos(angle)
        out[i, 1] = s * math.sin(angle)
    return out


@dataclass
class UnevenCircle:
    """Euler's uneven orbit of P94 (§833): XF = delta t + alpha sin At + phase, 1/s^3 = (1 + beta cos At)/f^3.

    f (mean distance, km), delta and A (rad per time unit), alpha, beta and phase (rad, -),
    one value per attracting mass; the orbit lies in the x-y plane.
    """

    names: tuple
    gm: np.ndarray
    f: np.ndarray
    delta: np.ndarray
    alpha: np.ndarray
    beta: np.ndarray
    a_freq: np.ndarray
    phase: np.ndarray = None
    span: tuple = (-math.inf, math.inf)
    data: tuple = field(init=False)

    def __post_init__(self):
        n = len(self.names)
        self.gm, self.f, self.delta, self.alpha, self.beta, self.a_freq, self.phase = _per_body(
            n, self.gm, self.f, self.delta, self.alpha, self.beta, self.a_freq, self.phase)
        if np.any(self.f <= 0):
            raise InputError("f", self.f.tolist(), "positive mean distances")
        if np.any(np.abs(self.beta) >= 1):
            raise InputError("beta", self.beta.tolist(), "|beta| < 1 (1/s^3 must stay positive)")
        self.data = (self.f, self.delta, self.alpha, self.beta, self.a_freq, self.phase)

    kernel = staticmethod(_uneven_circle_positions)

    def positions(self, t):
        return np.array([_uneven_circle_positions(ti, self.data) for ti in np.atleast_1d(t)])
