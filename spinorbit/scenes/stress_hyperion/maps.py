"""The map of Hyperion's planar Lyapunov exponent over initial (theta - f, theta'/n) at periapsis."""
import math

import numpy as np

from ..planar_spin_orbit import planar_lyapunov


def lyapunov_map(scenario, p, period):
    """(theta grid, rate/n grid, exponent (n_rate, n_theta) in 1/T) at periapsis after map.orbits periods."""
    n_theta, n_rate = (int(v) for v in scenario["map.grid"])
    theta = (np.arange(n_theta) + 0.5) * math.pi / n_theta
    lo, hi = scenario["map.rate_range"]
    rate = lo + (np.arange(n_rate) + 0.5) * (hi - lo) / n_rate
    th, rt = np.meshgrid(theta, rate)
    running = planar_lyapunov(p, th.ravel(), rt.ravel() * p[0], scenario.t_start, period,
                              scenario["map.orbits"], scenario["lyapunov.steps_per_orbit"] // 2,
                              scenario["lyapunov.d0"])
    return theta, rate, running[-1].reshape(th.shape)
