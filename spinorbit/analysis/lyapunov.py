"""Maximal Lyapunov exponents by two-trajectory renormalisation (Benettin et al. 1980).

Layer 2.  A reference and a neighbour trajectory start ``d0`` apart in a scaled
phase space (distance |(y_neighbour - y_reference) / scale|); after every
interval their distance d is measured, ln(d/d0) accumulated and the neighbour
pulled back to distance d0 along the same direction.  The running exponent after
k intervals is sum ln(d/d0) / k, per interval.  A regular orbit's falls like ln k / k;
a chaotic one's tends to a positive limit.

Any flow fits: ``advance(k, pairs) -> pairs`` carries n (reference, neighbour)
pairs, shape (n, 2, dim), over interval k.  The flows below cover a compiled
rhs on a vector of independent copies (all pairs in one integration), scipy's
DOP853 on the same, and a System integrated by any registered method.
"""
import math

import numpy as np

from ..integrators import simulate
from ..integrators.rk8 import fixed_step


def displaced(y0, d0, scale):
    """Pairs (n, 2, dim) from starts y0 (n, dim): each neighbour d0 away along the diagonal of the scaled space."""
    y0 = np.atleast_2d(np.asarray(y0, dtype=float))
    scale = np.asarray(scale, dtype=float)
    return np.stack([y0, y0 + scale * d0 / math.sqrt(y0.shape[1])], axis=1)


def benettin(advance, pairs, d0, intervals, scale):
    """Running exponents (intervals, n), per interval, of the pairs (n, 2, dim) under ``advance``."""
    pairs = np.array(pairs, dtype=float)
    scale = np.asarray(scale, dtype=float)
    logs, running = np.zeros(pairs.shape[0]), np.empty((intervals, pairs.shape[0]))
    for k in range(intervals):
        pairs = advance(k, pairs)
        diff = (pairs[:, 1] - pairs[:, 0]) / scale
        d = np.sqrt(np.sum(diff * diff, axis=1))
        logs += np.log(d / d0)
        running[k] = logs / (k + 1)
        pairs[:, 1] = pairs[:, 0] + scale * diff * (d0 / d)[:, None]
    return running


def compiled_flow(rhs, params, t0, interval, step):
    """advance() for a numba ``rhs(t, y, params)`` acting on a flat vector of independent copies (any number):
    every pair in one compiled rk8 run (integrators.rk8.fixed_step) of steps <= ``step``."""
    def advance(k, pairs):
        t = t0 + k * interval
        return fixed_step(rhs, params, t, pairs.ravel(), [t + interval], step)[0].reshape(pairs.shape)

    return advance


def scipy_flow(rhs, params, t0, interval, rtol=1e-12, atol=1e-12):
    """advance() as compiled_flow, with scipy's adaptive DOP853 (an independent integrator)."""
    from scipy.integrate import solve_ivp

    def advance(k, pairs):
        t = t0 + k * interval
        y = solve_ivp(rhs, (t, t + interval), pairs.ravel(), "DOP853", args=(params,), rtol=rtol, atol=atol).y
        return y[:, -1].reshape(pairs.shape)

    return advance


def system_flow(system, interval, method="rk8", **options):
    """advance() for a System: each state integrated on its own from system.t0 + k interval."""
    def advance(k, pairs):
        t = system.t0 + k * interval
        return np.array([[simulate(system.with_start(t, y), [t, t + interval], method, options,
                                   estimate_error=False)[0].y[-1] for y in pair] for pair in pairs])

    return advance


def ensemble_mean(exponents):
    """(mean, standard error of the mean) of independent finite-time exponents."""
    exponents = np.asarray(exponents, dtype=float)
    return float(np.mean(exponents)), float(np.std(exponents, ddof=1) / math.sqrt(exponents.size))
