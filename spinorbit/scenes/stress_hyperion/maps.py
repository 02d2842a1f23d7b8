"""The map of Hyperion's planar Lyapunov exponent over initial (theta - f, theta'/n) at periapsis."""
import math

import numpy as np

from ...analysis.planar_spin_orbit import planar_lyapunov


def lyapunov_map(p, planar, period):
    """(theta grid, rate/n grid, exponent (n_rate, n_theta) in 1/T) at periapsis after map.orbits periods."""
    n_theta, n_rate = (int(v) for v in p["map.grid"])
    theta = (np.arange(n_theta) + 0.5) * math.pi / n_theta
    lo, hi = p["map.rate_range"]
    rate = lo + (np.arange(n_rate) + 0.5) * (hi - lo) / n_rate
    th, rt = np.meshgrid(theta, rate)
    running = planar_lyapunov(planar, th.ravel(), rt.ravel() * planar[0], p.t_start, period,
                              p["map.orbits"], p["lyapunov.steps_per_orbit"] // 2,
                              p["lyapunov.d0"])
    return theta, rate, running[-1].reshape(th.shape)
