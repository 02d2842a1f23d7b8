"""Quintic Hermite interpolant of sampled positions, velocities and accelerations, built once per run.

The hot loop reads positions through the numba function :func:`hermite_positions`
(about a microsecond per call), never through an ephemeris reader.  Samples are
on a uniform TDB-day grid; outside it the kernel returns NaN (so the integrator
stops with IntegrationError) and :meth:`HermiteOrbits.positions` raises
EphemerisRangeError.

Each interval matches position, velocity and acceleration at both knots, so the
interpolant is C2 and its error is O(h^6): |x^(6)| h^6 / 46080 at mid-interval
(remainder x^(6)/6! (t - t_k)^3 (t - t_k+1)^3).  The cubic Hermite used before
(C1, O(h^4)) jumped in the second derivative at every knot, which cost rk8 its
eighth order once a step spanned several knots: Moon and Earth runs stalled near
1e-3" and 0.3 mas (benchmarks/RESULTS.md gives both).  Accelerations not given
are derived from the velocity samples by 7-point (sixth-order) differences, so
every source (JPL kernel, REBOUND) gets the same interpolant; on DE421 they match
the Chebyshev series' own second derivative to ~1e-8 relative (tests/test_orbits.py).
"""
import math

import numpy as np
from numba import njit

from ..base.errors import EphemerisRangeError, InputError


@njit(cache=True)
def _interval(t, data):
    """(k, x): t lies in the grid's interval k at fraction x; k = -1 outside the grid (or t NaN)."""
    grid, m = data[0], data[1].shape[1]
    s = (t - grid[0]) / grid[1]
    if not (s >= 0.0 and s <= m - 1):
        return -1, 0.0
    k = min(int(s), m - 2)
    return k, s - k


@njit(cache=True)
def _basis(x, h):
    """The quintic Hermite basis at fraction x of an interval h: weights of (p, v, a) at its two knots."""
    x1 = 1.0 - x
    x3, y3 = x * x * x, x1 * x1 * x1
    return (y3 * (1.0 + 3.0 * x + 6.0 * x * x), h * x * y3 * (1.0 + 3.0 * x), 0.5 * h * h * x * x * y3,
            x3 * (1.0 + 3.0 * x1 + 6.0 * x1 * x1), -h * x3 * x1 * (1.0 + 3.0 * x1), 0.5 * h * h * x3 * x1 * x1)


@njit(cache=True)
def _basis_rate(x, h):
    """d/dt of :func:`_basis`."""
    x1 = 1.0 - x
    dp = 30.0 * x * x * x1 * x1 / h
    return (-dp, x1 * x1 * (1.0 - 3.0 * x) * (1.0 + 5.0 * x), 0.5 * h * x * x1 * x1 * (2.0 - 5.0 * x),
            dp, x * x * (3.0 * x - 2.0) * (6.0 - 5.0 * x), -0.5 * h * x * x * x1 * (5.0 * x - 3.0))


@njit(cache=True)
def _combine(weights, data, k):
    """(n, 3): the basis ``weights`` applied to the samples at knots k and k + 1."""
    pos, vel, acc = data[1], data[2], data[3]
    p0, v0, a0, p1, v1, a1 = weights
    out = np.empty((pos.shape[0], 3))
    for i in range(pos.shape[0]):
        for j in range(3):
            out[i, j] = (p0 * pos[i, k, j] + v0 * vel[i, k, j] + a0 * acc[i, k, j]
                         + p1 * pos[i, k + 1, j] + v1 * vel[i, k + 1, j] + a1 * acc[i, k + 1, j])
    return out


@njit(cache=True)
def hermite_positions(t, data):
    """data = (grid [t0, h], positions (n, m, 3) km, velocities km/d, accelerations km/d^2) -> (n, 3) km."""
    k, x = _interval(t, data)
    if k < 0:
        return np.full((data[1].shape[0], 3), np.nan)
    return _combine(_basis(x, data[0][1]), data, k)


@njit(cache=True)
def hermite_states(t, data):
    """Positions (n, 3) km and velocities (n, 3) km/d at t: hermite_positions and its time derivative."""
    k, x = _interval(t, data)
    if k < 0:
        nan = np.full((data[1].shape[0], 3), np.nan)
        return nan, nan.copy()
    h = data[0][1]
    return _combine(_basis(x, h), data, k), _combine(_basis_rate(x, h), data, k)


def _weights(offsets):
    """First-derivative weights on integer ``offsets``, exact for polynomials of degree < len(offsets)."""
    rhs = np.zeros(len(offsets))
    rhs[1] = 1.0
    return np.linalg.solve(np.vander(offsets, len(offsets), increasing=True).T, rhs)


def derivative(samples, step, width=7):
    """d/dt of ``samples`` (n, m, 3) on a uniform grid of ``step`` days, ``width``-point differences.

    Centred stencils (order width - 1) inside, one-sided ones of the same width
    at the ends; fewer than ``width`` samples use them all.
    """
    m = samples.shape[1]
    width = min(width, m)
    half = width // 2
    out = np.empty_like(samples)
    centred = _weights(np.arange(width) - half)
    inner = range(half, m - (width - 1 - half))
    out[:, inner.start:inner.stop] = sum(w * samples[:, i:i + len(inner)] for i, w in enumerate(centred))
    for k in (*range(inner.start), *range(inner.stop, m)):
        first = min(max(k - half, 0), m - width)
        weights = _weights(np.arange(first, first + width) - k)
        out[:, k] = np.tensordot(weights, samples[:, first:first + width], axes=(0, 1))
    return out / step


@njit(cache=True)
def _positions_many(ts, data):
    out = np.empty((ts.shape[0], data[1].shape[0], 3))
    for k in range(ts.shape[0]):
        r = hermite_positions(ts[k], data)
        for i in range(r.shape[0]):
            for j in range(3):
                out[k, i, j] = r[i, j]
    return out


class HermiteOrbits:
    """Bodies sampled every ``step`` days from ``t_start``: spinorbit.orbits.Orbits.

    positions, velocities and (optional) accelerations: arrays (n_bodies, n_samples, 3),
    km, km/day, km/day^2, in the source's inertial axes, relative to the spinning body;
    accelerations default to :func:`derivative` of the velocities.  gm: km^3/day^2.
    """

    kernel = staticmethod(hermite_positions)

    def __init__(self, names, gm, t_start, step, positions, velocities, source="samples", accelerations=None):
        pos = np.ascontiguousarray(positions, dtype=float)
        vel = np.ascontiguousarray(velocities, dtype=float)
        self.names = tuple(names)
        self.gm = np.asarray(gm, dtype=float).reshape(len(self.names))
        if pos.ndim != 3 or pos.shape != vel.shape or pos.shape[0] != len(self.names) \
                or pos.shape[1] < 2 or pos.shape[2] != 3 \
                or (accelerations is not None and np.shape(accelerations) != pos.shape):
            raise InputError("positions/velocities/accelerations",
                                f"shapes {pos.shape}, {vel.shape}, {np.shape(accelerations)}",
                                f"equal shapes ({len(self.names)}, n_samples >= 2, 3)")
        if not step > 0:
            raise InputError("step", step, "a positive step in days")
        self.source = source
        self.step = float(step)
        self.span = (float(t_start), float(t_start) + (pos.shape[1] - 1) * self.step)
        acc = derivative(vel, self.step) if accelerations is None else accelerations
        self.data = (np.array([float(t_start), self.step]), pos, vel, np.ascontiguousarray(acc, dtype=float))
        self.max_error_km = None          # set by measure_error()
        self.max_relative_error = None
        self.jump = None                  # (body index, t, error km, typical error km) if a body jumps

    def check_span(self, t_start, t_end):
        """Raise EphemerisRangeError unless [t_start, t_end] lies inside the sampled span."""
        if not (self.span[0] <= t_start and t_end <= self.span[1]):
            raise EphemerisRangeError(f"{self.source} interpolant", (t_start, t_end), self.span,
                                      "The run sampled its orbits over its own span only")

    def positions(self, t):
        """Positions at TDB days ``t``: (len(t), n_bodies, 3) km."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        self.check_span(t.min(), t.max())
        return _positions_many(t, self.data)

    def measure_error(self, reference, max_points=8192):
        """Interpolation error at the grid's mid-points (where it peaks) against ``reference``.

        reference(t) -> (len(t), n_bodies, 3) km, the source the samples came from.
        Every mid-point, or ``max_points`` of them evenly spread over the span (the
        error follows the orbit's phase, which a stride through a long span samples
        densely).  Sets and returns ``max_error_km`` (n,) and ``max_relative_error`` (n,)
        = max |dr|/r; the point-mass torque 3 GM/r^3 u x (I u) then errs by at most
        ~5 |dr|/r of its scale 3 GM (C - A)/r^3 (3 |dr|/r from 1/r^3, 2 |dr|/r from u).
        """
        intervals = self.data[1].shape[1] - 1
        index = np.unique(np.linspace(0, intervals - 1, min(intervals, max_points)).round().astype(int))
        t = self.span[0] + self.step * (index + 0.5)
        true = reference(t)
        err = np.linalg.norm(self.positions(t) - true, axis=2)
        self.max_error_km = err.max(axis=0)
        self.max_relative_error = (err / np.linalg.norm(true, axis=2)).max(axis=0)
        self.jump = _jump(t, err, np.linalg.norm(true, axis=2))
        return self.max_error_km

    def __repr__(self):
        err = "" if self.max_error_km is None else \
            f", max error {', '.join(f'{e:.3g}' for e in self.max_error_km)} km"
        return (f"HermiteOrbits({self.names}, {self.source}, span {self.span[0]:.6g} to "
                f"{self.span[1]:.6g} d, step {self.step:g} d{err})")


# A smooth orbit's mid-point errors vary with the orbit by a few times (e, h^6 scaling);
# an interval holding a jump in the samples errs by half the jump.  Flag an interval
# erring JUMP_FACTOR times the median one and above JUMP_FLOOR of the distance.
JUMP_FACTOR = 1e3
JUMP_FLOOR = 1e-9


def _jump(t, err, distance):
    """(body, t, error, typical error) of the worst interval if it stands out as a jump, else None."""
    typical = np.median(err, axis=0)
    worst = err.argmax(axis=0)
    for body, k in enumerate(worst):
        if err[k, body] > max(JUMP_FACTOR * typical[body], JUMP_FLOOR * distance[k, body]):
            return body, float(t[k]), float(err[k, body]), float(typical[body])
    return None


def grid(t_start, t_end, step):
    """Times t_start + k * step, k = 0..n, with the last one at or after t_end (days)."""
    if not t_end > t_start:
        raise InputError("t_start/t_end", (t_start, t_end), "end after start")
    n = max(1, math.ceil((t_end - t_start) / step))
    n += t_start + n * step < t_end
    return t_start + step * np.arange(n + 1)


def turned(orbits, rate, t_ref):
    """``orbits`` (a HermiteOrbits) turned about the axis of ``rate`` (rad/d, inertial) by |rate| (t - t_ref):
    r' = R r, v' = R v + rate x r', sampled on the same grid (a precession added to, or taken from, an orbit)."""
    rate = np.asarray(rate, dtype=float)
    t0, step = orbits.data[0]
    pos, vel = orbits.data[1], orbits.data[2]
    t = t0 + step * np.arange(pos.shape[1])
    size = float(np.linalg.norm(rate))
    axis = rate / size if size else np.array([0.0, 0.0, 1.0])
    turn = size * (t - t_ref)
    c, s = np.cos(turn)[:, None], np.sin(turn)[:, None]

    def rotate(x):                                  # Rodrigues, each sample (n, 3) by its own angle
        return x * c + np.cross(axis, x) * s + np.outer(x @ axis, axis) * (1 - c)

    new_pos = np.array([rotate(p) for p in pos])
    new_vel = np.array([rotate(v) + np.cross(rate, r) for v, r in zip(vel, new_pos)])
    return HermiteOrbits(orbits.names, orbits.gm, t0, step, new_pos, new_vel, source=f"{orbits.source} (turned)")
