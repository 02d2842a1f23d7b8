"""Analytic orbits: Euler's uniform circle (ch. 16 P93, P96) and the Kepler ellipse (P94).

Times are in the scene's time unit (days for real scenes); the circle lies in
the inertial x-y plane unless an inclination is given (tilted about x).
"""
import math
from dataclasses import dataclass, field

import numpy as np
from numba import njit

from ..errors import ScenarioError


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
        as_array = lambda v, default: np.full(n, default) if v is None else np.asarray(v, dtype=float).reshape(n)
        self.gm = as_array(self.gm, 0.0)
        self.radius, self.rate = as_array(self.radius, 0.0), as_array(self.rate, 0.0)
        self.phase, self.inclination = as_array(self.phase, 0.0), as_array(self.inclination, 0.0)
        if np.any(self.radius <= 0):
            raise ScenarioError("orbit.radius", self.radius.tolist(), "positive distances")
        self.data = (self.radius, self.rate, self.phase, self.inclination)

    kernel = staticmethod(_circle_positions)

    def positions(self, t):
        return np.array([_circle_positions(ti, self.data) for ti in np.atleast_1d(t)])
