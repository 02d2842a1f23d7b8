"""Point-mass accelerations to first post-Newtonian order: the Einstein-Infeld-Hoffmann (EIH) equations
as JPL's ephemerides integrate them, with the PPN parameters beta = gamma = 1.

For body i attracted by bodies j (GM mu_j, barycentric position r, velocity v, Newtonian acceleration a,
r_ij = |r_j - r_i|), Folkner et al. 2014 (IPN PR 42-196) eq. 27, Moyer 2003 (DESCANSO monograph 2)
eq. 4-26, after Newhall, Standish & Williams 1983 (A&A 125, 150), with beta = gamma = 1:

    a_i = sum_j mu_j (r_j - r_i) / r_ij^3 * (1 + B_ij / c^2)                         [Newton + braces]
        + 1/c^2 sum_j mu_j / r_ij^3 [(r_i - r_j) . (4 v_i - 3 v_j)] (v_i - v_j)
        + 7/(2 c^2) sum_j mu_j a_j / r_ij

    B_ij = -4 sum_{k != i} mu_k / r_ik - sum_{k != j} mu_k / r_jk + v_i^2 + 2 v_j^2 - 4 v_i . v_j
           - 3/2 [(r_i - r_j) . v_j / r_ij]^2 + 1/2 (r_j - r_i) . a_j

The accelerations a_j inside the 1/c^2 terms are the Newtonian ones (the error is O(c^-4)).  The
coordinates are harmonic (barycentric, TDB); the frame is the inertial frame of ``pos``.  Units: km, day.
"""
import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from .base import Interaction


@njit(cache=True, nogil=True)
def newtonian(pos, gm):
    """Newtonian accelerations (N, 3) of N point masses, km/d^2, and the potentials
    sum_{k != i} mu_k / r_ik (N,), km^2/d^2, from positions pos (N, 3) km and GM gm (N,) km^3/d^2."""
    n = pos.shape[0]
    acc = np.zeros((n, 3))
    potential = np.zeros(n)
    for i in range(n):
        for j in range(i + 1, n):
            dx, dy, dz = pos[j, 0] - pos[i, 0], pos[j, 1] - pos[i, 1], pos[j, 2] - pos[i, 2]
            r = math.sqrt(dx * dx + dy * dy + dz * dz)
            inv_r3 = 1.0 / (r * r * r)
            acc[i, 0] += gm[j] * dx * inv_r3
            acc[i, 1] += gm[j] * dy * inv_r3
            acc[i, 2] += gm[j] * dz * inv_r3
            acc[j, 0] -= gm[i] * dx * inv_r3
            acc[j, 1] -= gm[i] * dy * inv_r3
            acc[j, 2] -= gm[i] * dz * inv_r3
            potential[i] += gm[j] / r
            potential[j] += gm[i] / r
    return acc, potential


@njit(cache=True, nogil=True)
def accelerations(pos, vel, gm, c, targets):
    """(newton (k, 3), correction (k, 3)), km/d^2: the Newtonian acceleration of each body in ``targets``
    (int64 indices into the N bodies) and its EIH 1/c^2 correction (module docstring; Folkner et al.
    2014 eq. 27), from barycentric pos (N, 3) km, vel (N, 3) km/d, gm (N,) km^3/d^2, c in km/d."""
    n = pos.shape[0]
    acc, potential = newtonian(pos, gm)
    newton = np.empty((targets.shape[0], 3))
    correction = np.zeros((targets.shape[0], 3))
    d = np.empty(3)
    for m in range(targets.shape[0]):
        i = targets[m]
        vi = vel[i]
        vi2 = vi[0] * vi[0] + vi[1] * vi[1] + vi[2] * vi[2]
        for x in range(3):
            newton[m, x] = acc[i, x]
        for j in range(n):
            if j == i or gm[j] == 0.0:
                continue
            vj = vel[j]
            for x in range(3):
                d[x] = pos[j, x] - pos[i, x]                     # r_j - r_i
            r = math.sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])
            vj2 = vj[0] * vj[0] + vj[1] * vj[1] + vj[2] * vj[2]
            vivj = vi[0] * vj[0] + vi[1] * vj[1] + vi[2] * vj[2]
            n_vj = -(d[0] * vj[0] + d[1] * vj[1] + d[2] * vj[2]) / r
            d_aj = d[0] * acc[j, 0] + d[1] * acc[j, 1] + d[2] * acc[j, 2]
            braces = (-4.0 * potential[i] - potential[j] + vi2 + 2.0 * vj2 - 4.0 * vivj
                      - 1.5 * n_vj * n_vj + 0.5 * d_aj)
            f = gm[j] / (r * r * r)
            lever = -(d[0] * (4.0 * vi[0] - 3.0 * vj[0]) + d[1] * (4.0 * vi[1] - 3.0 * vj[1])
                      + d[2] * (4.0 * vi[2] - 3.0 * vj[2]))      # (r_i - r_j) . (4 v_i - 3 v_j)
            for x in range(3):
                correction[m, x] += (f * braces * d[x] + f * lever * (vi[x] - vj[x])
                                     + 3.5 * gm[j] / r * acc[j, x])
        for x in range(3):
            correction[m, x] /= c * c
    return newton, correction


@dataclass(frozen=True)
class Relativity(Interaction):
    """The EIH 1/c^2 correction to the point-mass accelerations of the bodies in the state (a pair's relative
    orbit; with every centre in the state, every body's); ``c_km_d`` the speed of light (DE421's CLIGHT in km/d)."""

    c_km_d: float
    phase = "orbit"
    citation = "Folkner et al. 2014 (IPN PR 42-196), eq. 27; Moyer 2003, eq. 4-26"

    def bodies(self):
        return ()

    def emit(self, code):
        motion = code.system.motion
        x, w, mu = motion.point_masses(code)
        correction = code.local("eih")
        code.line(f"{correction} = {code.bind(accelerations)}({x}, {w}, {mu}, {code.param('c_km_d', self.c_km_d)}, "
                  f"{code.param('eih_targets', motion.accelerated_rows())})[1]")
        motion.add_point_mass_accelerations(code, correction)
