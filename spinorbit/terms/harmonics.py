"""The figure's own degree-3 and higher gravity field acted on by each point mass.

Torque on the figure (per M R^2, R the field's reference radius), and the field's pull on the
mass, from the potential per unit GM of the body W = (1/r) sum_n (R/r)^n P_nm (C cos + S sin):

    N = -(GM/R^2) r x grad W(r),     F = (GM/R^2) grad W(r)     (so r x F = -N)

(Williams, Boggs & Folkner 2008; Folkner et al. 2014, IPN PR 42-196, eq. for the figure
torque; the gradient by the Cartesian V_nm/W_nm recursion of Montenbruck & Gill 2000,
§3.2.4-3.2.5, free of polar singularities).  Degree 2 is the point_mass term's.
"""
import math

import numpy as np
from numba import njit

from ..rotations import cross3, mat_t_vec3, matvec3
from .base import Term


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


@njit(cache=True, nogil=True)
def torque(t, y, rot, inertia, r_icrf, gm, p):
    """Sum over the masses of -(GM/R^2) r x grad W (body axes, per M R^2); p = (R km, C_nm, S_nm, n_min, n_max)."""
    radius, c_nm, s_nm, n_min, n_max = p
    total = np.zeros(3)
    for i in range(gm.shape[0]):
        r = mat_t_vec3(rot, r_icrf[i])
        total -= gm[i] / (radius * radius) * cross3(r, gradient(r, radius, c_nm, s_nm, n_min, n_max))
    return total


@njit(cache=True, nogil=True)
def force(t, y, rot, inertia, r_icrf, gm, p):
    """The field's pull (GM/R^2) grad W on each mass (n, 3), ICRF, per M R^2 per km."""
    radius, c_nm, s_nm, n_min, n_max = p
    out = np.zeros((gm.shape[0], 3))
    for i in range(gm.shape[0]):
        r = mat_t_vec3(rot, r_icrf[i])
        out[i] = matvec3(rot, gm[i] / (radius * radius) * gradient(r, radius, c_nm, s_nm, n_min, n_max))
    return out


@njit(cache=True, nogil=True)
def energy(t, y, rot, inertia, r_icrf, gm, p):
    """The masses' energy in the field, sum of -(GM/R^2) W(r) (per M R^2, the unit of ``torque``): F = -grad_r of it."""
    radius, c_nm, s_nm, n_min, n_max = p
    total = 0.0
    for i in range(gm.shape[0]):
        total -= gm[i] / (radius * radius) * potential(mat_t_vec3(rot, r_icrf[i]), radius, c_nm, s_nm, n_min, n_max)
    return total


def build(context):
    """The body's whole field from degree 3 (its ``radius_km`` and unnormalised ``c_nm``, ``s_nm``)."""
    body = context.body
    c_nm = np.ascontiguousarray(body.c_nm, dtype=float)
    params = (float(body.radius_km), c_nm, np.ascontiguousarray(body.s_nm, dtype=float), 3, c_nm.shape[0] - 1)
    return Term("harmonics", torque, params, force, "Folkner et al. 2014 (IPN PR 42-196); Montenbruck & Gill §3.2")
