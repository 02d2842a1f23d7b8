"""Euler's planar libration (§825-831): the body turning about its axis C normal to a circular orbit, started
at an angle zeta from the attracting body's direction F, and the angle zeta read back from a run."""
import math

import numpy as np

from ..base.rotations import matrices_from_quats
from ..models.assemblies.idealised import under_point_masses


def planar_system(moments, orbit, t0, zeta0, zeta_dot0, delta):
    """Body turning about z with A at angle (delta t0 - zeta0) from x; omega_z = delta - zeta' (§825)."""
    lam = delta * t0 - zeta0
    q0 = np.array([math.cos(lam / 2), 0.0, 0.0, math.sin(lam / 2)])
    return under_point_masses(moments, orbit, q0, [0.0, 0.0, delta - zeta_dot0], t0, "planar libration")


def zeta_from_solution(solution, f_longitude):
    """zeta = longitude of F - longitude of the body's A axis, unwrapped (rad)."""
    m = matrices_from_quats(solution.quaternion)
    lam = np.arctan2(m[:, 1, 0], m[:, 0, 0])
    return np.unwrap(f_longitude - lam)


def crossing_times(t, x, level=0.0):
    """Times where x crosses ``level`` upwards, by linear interpolation."""
    i = np.nonzero((x[:-1] < level) & (x[1:] >= level))[0]
    return t[i] + (level - x[i]) * (t[i + 1] - t[i]) / (x[i + 1] - x[i])
