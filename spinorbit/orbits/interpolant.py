"""Cubic Hermite interpolant of sampled positions and velocities, built once per run.

The hot loop reads positions through the numba function :func:`hermite_positions`
(about a microsecond per call), never through an ephemeris reader.  Samples are
on a uniform TDB-day grid; outside it the kernel returns NaN (so the integrator
stops with IntegrationError) and :meth:`HermiteOrbits.positions` raises
EphemerisRangeError.  The interpolation error is O(h^4): max |x''''| h^4 / 384.
"""
import math

import numpy as np
from numba import njit

from ..errors import EphemerisRangeError, ScenarioError


@njit(cache=True)
def hermite_positions(t, data):
    """data = (grid [t0, h], positions (n, m, 3) km, velocities (n, m, 3) km/d) -> (n, 3) km."""
    grid, pos, vel = data
    n, m = pos.shape[0], pos.shape[1]
    h = grid[1]
    s = (t - grid[0]) / h
    out = np.empty((n, 3))
    if not (s >= 0.0 and s <= m - 1):        # also catches t = NaN
        out[:] = np.nan
        return out
    k = min(int(s), m - 2)
    x = s - k
    x1 = 1.0 - x
    h00, h01 = (1.0 + 2.0 * x) * x1 * x1, x * x * (3.0 - 2.0 * x)
    h10, h11 = x * x1 * x1 * h, -x * x * x1 * h
    for i in range(n):
        for j in range(3):
            out[i, j] = (h00 * pos[i, k, j] + h10 * vel[i, k, j]
                         + h01 * pos[i, k + 1, j] + h11 * vel[i, k + 1, j])
    return out


@njit(cache=True)
def _positions_many(ts, data):
    out = np.empty((ts.shape[0], data[1].shape[0], 3))
    for k in range(ts.shape[0]):
        out[k] = hermite_positions(ts[k], data)
    return out


class HermiteOrbits:
    """Bodies sampled every ``step`` days from ``t_start``: an OrbitSource.

    positions, velocities: arrays (n_bodies, n_samples, 3), km and km/day, in the
    source's inertial axes, relative to the spinning body.  gm: km^3/day^2.
    """

    kernel = staticmethod(hermite_positions)

    def __init__(self, names, gm, t_start, step, positions, velocities, source="samples"):
        pos = np.ascontiguousarray(positions, dtype=float)
        vel = np.ascontiguousarray(velocities, dtype=float)
        self.names = tuple(names)
        self.gm = np.asarray(gm, dtype=float).reshape(len(self.names))
        if pos.ndim != 3 or pos.shape != vel.shape or pos.shape[0] != len(self.names) \
                or pos.shape[1] < 2 or pos.shape[2] != 3:
            raise ScenarioError("positions/velocities", f"shapes {pos.shape}, {vel.shape}",
                                f"equal shapes ({len(self.names)}, n_samples >= 2, 3)")
        if not step > 0:
            raise ScenarioError("step", step, "a positive step in days")
        self.source = source
        self.step = float(step)
        self.span = (float(t_start), float(t_start) + (pos.shape[1] - 1) * self.step)
        self.data = (np.array([float(t_start), self.step]), pos, vel)
        self.max_error_km = None          # set by measure_error()
        self.max_relative_error = None

    def check_span(self, t_start, t_end):
        """Raise EphemerisRangeError unless [t_start, t_end] lies inside the sampled span."""
        if not (self.span[0] <= t_start and t_end <= self.span[1]):
            raise EphemerisRangeError(f"{self.source} interpolant", f"{t_start:.6g} to {t_end:.6g}",
                                      self.span)

    def positions(self, t):
        """Positions at TDB days ``t``: (len(t), n_bodies, 3) km."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        self.check_span(t.min(), t.max())
        return _positions_many(t, self.data)

    def measure_error(self, reference):
        """Interpolation error at every mid-point of the grid against ``reference``.

        reference(t) -> (len(t), n_bodies, 3) km, the source the samples came from.
        Sets and returns ``max_error_km`` (n,) and ``max_relative_error`` (n,) = max |dr|/r;
        the point-mass torque 3 GM/r^3 u x (I u) then errs by at most ~5 |dr|/r of its
        scale 3 GM (C - A)/r^3 (3 |dr|/r from 1/r^3, 2 |dr|/r from the direction u).
        """
        t = self.span[0] + self.step * (np.arange(self.data[1].shape[1] - 1) + 0.5)
        true = reference(t)
        err = np.linalg.norm(self.positions(t) - true, axis=2)
        self.max_error_km = err.max(axis=0)
        self.max_relative_error = (err / np.linalg.norm(true, axis=2)).max(axis=0)
        return self.max_error_km

    def __repr__(self):
        err = "" if self.max_error_km is None else \
            f", max error {', '.join(f'{e:.3g}' for e in self.max_error_km)} km"
        return (f"HermiteOrbits({self.names}, {self.source}, span {self.span[0]:.6g} to "
                f"{self.span[1]:.6g} d, step {self.step:g} d{err})")


def grid(t_start, t_end, step):
    """Times t_start + k * step, k = 0..n, with the last one at or after t_end (days)."""
    if not t_end > t_start:
        raise ScenarioError("span", (t_start, t_end), "end after start")
    n = max(1, math.ceil((t_end - t_start) / step))
    n += t_start + n * step < t_end
    return t_start + step * np.arange(n + 1)
