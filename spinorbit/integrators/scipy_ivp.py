"""Adaptive reference integrators from scipy.integrate.solve_ivp (DOP853, Radau, RK45).

These are the yardstick everything else is checked against; their cost per
step is dominated by Python call overhead (one compiled rhs call per stage).
"""
import time
from typing import ClassVar

import numpy as np
from scipy.integrate import solve_ivp

from ..base.errors import IntegrationError
from .base import Integrator, Trajectory, check_finite, normalised
from .options import ATOL, MAX_STEP, RTOL


class ScipyIVP(Integrator):
    """scipy ``solve_ivp`` with the compiled rhs; ``rtol``/``atol`` are relative/absolute tolerances."""

    kind = "adaptive"
    scipy_method = "DOP853"
    options: ClassVar[dict] = {"rtol": RTOL(1e-12), "atol": ATOL(1e-14), "max_step": MAX_STEP}

    @classmethod
    def ladder(cls, time_scale, spacing):
        """rtol = 1e-3 ... 1e-13, atol = rtol / 1000."""
        return [{"rtol": 10.0**-k, "atol": 10.0**-k * 1e-3} for k in range(3, 14)]

    def solve(self, system, t_out):
        t_out = self._check_times(system, t_out)
        rhs, params = system.rhs, system.params
        nfev = [0]
        last_finite = [system.t0, system.y0, False]   # farthest (t, y) from t0 with a finite rhs; saw a NaN?
        direction = 1.0 if t_out[-1] >= system.t0 else -1.0

        def fun(t, y):
            nfev[0] += 1
            dy = rhs(t, y, params)
            if not np.all(np.isfinite(dy)):
                last_finite[2] = True
            elif direction * (t - last_finite[0]) >= 0.0:
                last_finite[:2] = t, y
            return dy

        if not np.all(np.isfinite(fun(system.t0, system.y0))):   # (also compiles outside the timed region)
            err = IntegrationError(f"{self.name}: the right-hand side is not finite at the start", system.t0,
                                   system.y0, "Check the initial state and the model's parameters.")
            err.partial = Trajectory(np.empty(0), np.empty((0, system.y0.size)), self.name, 1, None, 0.0,
                                   dict(self.settings))
            raise err                      # scipy's first step would be NaN and never shrink below its floor
        nfev[0] = 0
        start = time.perf_counter()
        sol = solve_ivp(fun, (system.t0, t_out[-1]), system.y0, method=self.scipy_method,
                        t_eval=t_out, rtol=self.settings["rtol"], atol=self.settings["atol"],
                        max_step=self.settings["max_step"])
        wall = time.perf_counter() - start
        t = np.asarray(sol.t, dtype=float)                # lists when it failed before the first output
        y = np.asarray(sol.y, dtype=float).reshape(system.y0.size, t.size).T
        partial = Trajectory(t, normalised(system, y), self.name, nfev[0], None, wall, dict(self.settings),
                           system.layout)               # solve_ivp does not report its steps
        if sol.status != 0:
            t_fail, y_fail, nan = last_finite
            advice = ("The right-hand side became non-finite just after this time: check the torque model "
                      "and the scene for a close encounter." if nan else
                      "Loosen rtol/atol or try method 'radau' for stiff cases.")
            err = IntegrationError(f"{self.name}: {sol.message}", float(t_fail), np.array(y_fail), advice)
            err.partial = partial
            raise err
        check_finite(y, t_out[-1], self.name, partial)
        return partial


class DOP853(ScipyIVP):
    """Dormand-Prince 8(5,3) explicit Runge-Kutta (order 8), adaptive."""
    name, order, scipy_method = "dop853", 8, "DOP853"


class Radau(ScipyIVP):
    """Radau IIA implicit Runge-Kutta (order 5), adaptive; for stiff problems."""
    name, order, scipy_method = "radau", 5, "Radau"
    options: ClassVar[dict] = {"rtol": RTOL(1e-10), "atol": ATOL(1e-12), "max_step": MAX_STEP}


class RK45(ScipyIVP):
    """Dormand-Prince 5(4), adaptive."""
    name, order, scipy_method = "rk45", 5, "RK45"
    options: ClassVar[dict] = {"rtol": RTOL(1e-9), "atol": ATOL(1e-12), "max_step": MAX_STEP}
