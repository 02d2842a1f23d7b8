"""Compiled fixed-step explicit Runge-Kutta of order 8 (the DOP853 tableau, Hairer & Wanner).

The whole loop runs in numba: the right-hand side is a numba function
``rhs(t, y, p)`` and is called 12 times per step, with no Python in between.
Use it where the step can be chosen once (smooth forcing); it reaches the
rounding floor (about 1e-12 relative in the attitude) at h ~ 1 d for the Moon.
"""
import time

import numpy as np
from numba import njit
from scipy.integrate._ivp import dop853_coefficients as _dop853

from ..errors import IntegrationError, ScenarioError
from .base import Integrator, Solution, normalise_quaternions


@njit
def _rk_fixed(rhs, params, t0, y0, t_out, h, a, b, c, max_steps):
    """Integrate with fixed step <= h, landing exactly on every output time.

    Returns (y_out, n_done, steps, t_fail): n_done < len(t_out) when the state
    became non-finite (then t_fail is where).
    """
    n_stages = b.shape[0]
    dim = y0.shape[0]
    y_out = np.empty((t_out.shape[0], dim))
    k = np.empty((n_stages, dim))
    y = y0.copy()
    ys = np.empty(dim)
    t = t0
    steps = 0
    for i in range(t_out.shape[0]):
        span = t_out[i] - t
        n_sub = int(np.ceil(span / h - 1e-12)) if span > 0 else 0
        dt = span / n_sub if n_sub > 0 else 0.0
        for _ in range(n_sub):
            for s in range(n_stages):
                ys[:] = y
                for j in range(s):
                    if a[s, j] != 0.0:
                        w = dt * a[s, j]
                        for m in range(dim):
                            ys[m] += w * k[j, m]
                k[s] = rhs(t + c[s] * dt, ys, params)
            for s in range(n_stages):
                if b[s] != 0.0:
                    w = dt * b[s]
                    for m in range(dim):
                        y[m] += w * k[s, m]
            t += dt
            steps += 1
            if steps > max_steps or not np.all(np.isfinite(y)):
                return y_out, i, steps, t
        y_out[i] = y
        t = t_out[i]
    return y_out, t_out.shape[0], steps, t


class RK8(Integrator):
    """Fixed-step 8th-order explicit Runge-Kutta, compiled; option ``step`` (time units, days)."""

    name, order, kind = "rk8", 8, "fixed"
    options = {"step": 1.0, "max_steps": 10**9}
    # Butcher tableau (methods as data): the 12-stage 8th-order part of DOP853.
    A = np.ascontiguousarray(_dop853.A[:12, :12])
    B = np.ascontiguousarray(_dop853.B)
    C = np.ascontiguousarray(_dop853.C[:12])

    def solve(self, system, t_out):
        t_out = self._check_times(system, t_out)
        h = float(self.settings["step"])
        if not h > 0:
            raise ScenarioError("integrator.step", h, "a positive step in days")
        args = (system.rhs, system.params, float(system.t0), system.y0, t_out, h, self.A, self.B, self.C,
                int(self.settings["max_steps"]))
        _rk_fixed(*args[:4], t_out[:1], *args[5:])          # compile outside the timed region
        start = time.perf_counter()
        y, n_done, steps, t_fail = _rk_fixed(*args)
        wall = time.perf_counter() - start
        solution = Solution(t_out[:n_done], normalise_quaternions(y[:n_done]), self.name,
                            steps * len(self.B), steps, wall, dict(self.settings))
        if n_done < t_out.size:
            reason = "exceeded max_steps" if steps > self.settings["max_steps"] else "state became non-finite"
            err = IntegrationError(f"{self.name}: {reason}", t_fail, y[n_done - 1] if n_done else system.y0,
                                   "Raise integrator.max_steps." if steps > self.settings["max_steps"] else
                                   "Reduce integrator.step, or use an adaptive method (dop853) to find the difficulty.")
            err.partial = solution
            raise err
        return solution
