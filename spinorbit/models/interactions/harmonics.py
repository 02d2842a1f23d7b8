"""The figure's own gravity field beyond degree 2, acted on by point masses.

Torque on the figure and the field's pull on each mass, from the potential per unit GM of the body
W = (1/r) sum_n (R/r)^n P_nm (C cos + S sin), G-scaled by the body's GM R^2 (its field's inertia unit):

    N = -GM_body GM r x grad W(r),     F = GM_body GM grad W(r)     (so r x F = -N)

(Williams, Boggs & Folkner 2008; Folkner et al. 2014, IPN PR 42-196, the figure torque; the gradient by
the Cartesian V_nm/W_nm recursion of Montenbruck & Gill 2000, §3.2.4-3.2.5, free of polar singularities).
Degree 2 is the point-mass term's (the figure's inertia).
"""
import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ...base.linker import cached
from ...base.rotations import cross3, mat_t_vec3, matvec3
from .base import Interaction
from .point_mass import act


@njit(cache=True, nogil=True)
def _recursion(r, radius, top):
    """Montenbruck & Gill's V_nm, W_nm (n, m <= top) at r (body axes, km): (R/r)^(n+1) P_nm (cos, sin) m lambda."""
    x, y, z = r[0], r[1], r[2]
    r2 = x * x + y * y + z * z
    rho = radius * radius / r2
    x0, y0, z0 = radius * x / r2, radius * y / r2, radius * z / r2
    v = np.zeros((top + 1, top + 1))
    w = np.zeros((top + 1, top + 1))
    v[0, 0] = radius / math.sqrt(r2)
    for m in range(top + 1):
        if m > 0:
            v[m, m] = (2 * m - 1) * (x0 * v[m - 1, m - 1] - y0 * w[m - 1, m - 1])
            w[m, m] = (2 * m - 1) * (x0 * w[m - 1, m - 1] + y0 * v[m - 1, m - 1])
        if m < top:
            v[m + 1, m] = (2 * m + 1) * z0 * v[m, m]
            w[m + 1, m] = (2 * m + 1) * z0 * w[m, m]
        for n in range(m + 2, top + 1):
            v[n, m] = ((2 * n - 1) * z0 * v[n - 1, m] - (n + m - 1) * rho * v[n - 2, m]) / (n - m)
            w[n, m] = ((2 * n - 1) * z0 * w[n - 1, m] - (n + m - 1) * rho * w[n - 2, m]) / (n - m)
    return v, w


@njit(cache=True, nogil=True)
def potential(r, radius, c_nm, s_nm, n_min, n_max):
    """W at r (body axes, km), degrees n_min..n_max: sum (C_nm V_nm + S_nm W_nm) / R, 1/km."""
    v, w = _recursion(r, radius, n_max)
    total = 0.0
    for n in range(n_min, n_max + 1):
        for m in range(n + 1):
            total += c_nm[n, m] * v[n, m] + s_nm[n, m] * w[n, m]
    return total / radius


@njit(cache=True, nogil=True)
def gradient(r, radius, c_nm, s_nm, n_min, n_max):
    """grad W at r (body axes, km), degrees n_min..n_max, unnormalised coefficients (C_n0 = -J_n): 1/km^2."""
    v, w = _recursion(r, radius, n_max + 1)
    ax = ay = az = 0.0
    for n in range(n_min, n_max + 1):
        c = c_nm[n, 0]
        ax -= c * v[n + 1, 1]
        ay -= c * w[n + 1, 1]
        az -= (n + 1) * c * v[n + 1, 0]
        for m in range(1, n + 1):
            c, s = c_nm[n, m], s_nm[n, m]
            fac = (n - m + 2) * (n - m + 1)
            ax += 0.5 * (-c * v[n + 1, m + 1] - s * w[n + 1, m + 1]
                         + fac * (c * v[n + 1, m - 1] + s * w[n + 1, m - 1]))
            ay += 0.5 * (-c * w[n + 1, m + 1] + s * v[n + 1, m + 1]
                         + fac * (-c * w[n + 1, m - 1] + s * v[n + 1, m - 1]))
            az += (n - m + 1) * (-c * v[n + 1, m] - s * w[n + 1, m])
    r_ref2 = radius * radius
    return np.array([ax / r_ref2, ay / r_ref2, az / r_ref2])


@cached(nogil=True)
def torque(rot, rows, gm, scale, radius, c_nm, s_nm, n_min, n_max):
    """Sum over the masses of -scale GM/R^2 r x grad W, body axes; ``scale`` = GM_body R^2 (km^5/d^2)."""
    total = np.zeros(3)
    for i in range(gm.shape[0]):
        r = mat_t_vec3(rot, rows[i])
        total -= scale * gm[i] / (radius * radius) * cross3(r, gradient(r, radius, c_nm, s_nm, n_min, n_max))
    return total


@cached(nogil=True)
def force(rot, rows, gm, scale, radius, c_nm, s_nm, n_min, n_max):
    """The field's pull scale GM/R^2 grad W on each mass (n, 3), inertial axes."""
    out = np.zeros((gm.shape[0], 3))
    for i in range(gm.shape[0]):
        r = mat_t_vec3(rot, rows[i])
        out[i] = matvec3(rot, scale * gm[i] / (radius * radius) * gradient(r, radius, c_nm, s_nm, n_min, n_max))
    return out


@cached(nogil=True)
def energy(rot, rows, gm, scale, radius, c_nm, s_nm, n_min, n_max):
    """The masses' energy in the field, sum of -scale GM/R^2 W(r): F = -grad_r of it."""
    total = 0.0
    for i in range(gm.shape[0]):
        total -= scale * gm[i] / (radius * radius) * potential(mat_t_vec3(rot, rows[i]), radius, c_nm, s_nm,
                                                                n_min, n_max)
    return total


@dataclass(frozen=True)
class Harmonics(Interaction):
    """``attractors`` as point masses on ``figure``'s field beyond degree 2 (``Figure.field``)."""

    figure: str
    attractors: tuple
    citation = "Folkner et al. 2014 (IPN PR 42-196); Montenbruck & Gill 2000, §3.2"

    def bodies(self):
        return (self.figure, *self.attractors)

    def tidal_attractors(self, name):
        """None: the field beyond degree 2 does not move a gyroscopic body's figure axis here (its Oppolzer terms
        come from the degree-2 tidal tensor alone)."""
        return ()

    def _args(self, code, rows, gm):
        body = code.system.bodies[self.figure]
        field = body.figure.field
        name = self.figure
        return (f"({code.rot(name)}, {rows}, {gm}, "
                f"{code.param(f'{name}_field_scale', body.gm * field.radius_km ** 2)}, "
                f"{code.param(f'{name}_field_radius', float(field.radius_km))}, "
                f"{code.param(f'{name}_c_nm', np.ascontiguousarray(field.c_nm, dtype=float))}, "
                f"{code.param(f'{name}_s_nm', np.ascontiguousarray(field.s_nm, dtype=float))}, "
                f"{code.param(f'{name}_field_n_min', int(field.n_min))}, "
                f"{code.param(f'{name}_field_n_max', int(field.n_max))})")

    def emit(self, code):
        rows, gm = code.rows(self.figure, self.attractors)
        args = self._args(code, rows, gm)
        act(code, self.figure, self.attractors, rows, f"{code.bind(torque, 'harmonics_torque')}{args}",
            f"{code.bind(force, 'harmonics_force')}{args}")

    def energy(self, code):
        rows, gm = code.rows(self.figure, self.attractors)
        return f"{code.bind(energy, 'harmonics_energy')}{self._args(code, rows, gm)}"
