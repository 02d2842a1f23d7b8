"""An oblate attractor's J2 on the degree-2 figure (figure-figure), e.g. the Earth's J2 on the Moon.

Folkner et al. 2014 (IPN PR 42-196), the figure-figure torque N_figM-figE on the Moon's
inertia I from the Earth's J2, with u = r/r (the attractor seen from the figure), p its unit
pole and s = u.p (all in the figure's body axes):

    N = 15 GM J2 R^2 / (2 r^5) [ (1 - 7 s^2) u x I u + 2 s (u x I p + p x I u) - 2/5 p x I p ]

It derives from the interaction energy of the figure in the attractor's J2 potential,
E = -1/2 I : grad grad U_J2 (U_J2 = GM J2 R^2 (3 (p.x)^2/x^2 - 1) / (2 x^3), harmonic, so
the trace of I drops out).  The force on the attractor and the torque on its own figure follow
from E by differentiation, here by the complex step (exact to rounding): F = -grad_r E,
N_attractor = -p x grad_p E; action equals reaction (rot N + r x F + N_attractor = 0).
"""
import math

import numpy as np
from numba import njit

from ..bodies.de421_header import header
from ..rotations import cross3, dot3, mat_t_vec3, matvec3
from .base import Term, anisotropic

_STEP = 1e-20           # complex step, relative to the vector differentiated


@njit(cache=True, nogil=True)
def pole_at(t, grid, samples):
    """Unit vector at TDB day t, linear in the table (grid [t0, h], (m, 3) samples), clamped to its ends."""
    s = min(max((t - grid[0]) / grid[1], 0.0), samples.shape[0] - 1.000001)
    k = int(s)
    v = samples[k] + (s - k) * (samples[k + 1] - samples[k])
    return v / math.sqrt(dot3(v, v))


@njit(cache=True, nogil=True)
def figure_torque(inertia, r, pole, gm_j2_r2):
    """Folkner et al. 2014 N_figM-figE (body axes): r the attractor from the figure (km), pole its unit pole."""
    inertia = anisotropic(inertia)
    r2 = dot3(r, r)
    rn = math.sqrt(r2)
    u = r / rn
    s = dot3(u, pole)
    iu, ip = matvec3(inertia, u), matvec3(inertia, pole)
    return 7.5 * gm_j2_r2 / (r2 * r2 * rn) * ((1.0 - 7.0 * s * s) * cross3(u, iu)
                                              + 2.0 * s * (cross3(u, ip) + cross3(pole, iu))
                                              - 0.4 * cross3(pole, ip))


@njit(cache=True, nogil=True)
def energy(inertia, x, pole, gm_j2_r2):
    """E = -1/2 I : grad grad U_J2 at x (real or complex: the complex step differentiates it)."""
    inertia = anisotropic(inertia)              # grad grad U_J2 is trace-free: the isotropic part adds 0
    r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2]
    r = np.sqrt(r2)
    s = pole[0] * x[0] + pole[1] * x[1] + pole[2] * x[2]
    inv5 = 1.0 / (r2 * r2 * r)
    inv7, inv9 = inv5 / r2, inv5 / (r2 * r2)
    total = 0.0 * r2
    for i in range(3):
        for j in range(3):
            d = 1.0 if i == j else 0.0
            ss = (2.0 * pole[i] * pole[j] * inv5 - 10.0 * s * (pole[i] * x[j] + pole[j] * x[i]) * inv7
                  - 5.0 * s * s * d * inv7 + 35.0 * s * s * x[i] * x[j] * inv9)
            rr = 15.0 * x[i] * x[j] * inv7 - 3.0 * d * inv5
            total += inertia[i, j] * (3.0 * ss - rr)
    return -0.25 * gm_j2_r2 * total


@njit(cache=True, nogil=True)
def _energy_gradient(inertia, r, pole, gm_j2_r2, of_pole):
    """grad E with respect to r (of_pole False) or to the pole (True), by the complex step."""
    out = np.zeros(3)
    scale = math.sqrt(dot3(pole, pole) if of_pole else dot3(r, r))
    for m in range(3):
        rc, pc = r.astype(np.complex128), pole.astype(np.complex128)
        if of_pole:
            pc[m] += 1j * _STEP * scale
        else:
            rc[m] += 1j * _STEP * scale
        out[m] = energy(inertia, rc, pc, gm_j2_r2).imag / (_STEP * scale)
    return out


@njit(cache=True, nogil=True)
def torque(t, y, rot, inertia, r_icrf, gm, p):
    """Body-axes torque of attractor p[0]'s J2 (p = (index, GM J2 R^2 km^5/d^2, pole grid, pole samples))."""
    index, gm_j2_r2, grid, samples = p
    return figure_torque(inertia, mat_t_vec3(rot, r_icrf[index]), mat_t_vec3(rot, pole_at(t, grid, samples)),
                         gm_j2_r2)


@njit(cache=True, nogil=True)
def force(t, y, rot, inertia, r_icrf, gm, p):
    """Force on the attractor (row p[0]; the others zero), ICRF: -grad_r E."""
    index, gm_j2_r2, grid, samples = p
    out = np.zeros((gm.shape[0], 3))
    pole = mat_t_vec3(rot, pole_at(t, grid, samples))
    out[index] = -matvec3(rot, _energy_gradient(inertia, mat_t_vec3(rot, r_icrf[index]), pole, gm_j2_r2, False))
    return out


@njit(cache=True, nogil=True)
def reaction_torque(t, y, rot, inertia, r_icrf, gm, p):
    """Torque on the attractor's own figure, ICRF: -p x grad_p E."""
    index, gm_j2_r2, grid, samples = p
    pole = mat_t_vec3(rot, pole_at(t, grid, samples))
    grad = _energy_gradient(inertia, mat_t_vec3(rot, r_icrf[index]), pole, gm_j2_r2, True)
    return matvec3(rot, -cross3(pole, grad))


@njit(cache=True, nogil=True)
def with_pole(rot, inertia, r_icrf, pole_icrf, gm_j2_r2):
    """The term with the attractor's unit pole given directly (ICRF), e.g. from its own attitude, instead of a
    pole table: (torque on the figure, body axes; force on the attractor, ICRF; torque on the attractor's
    figure, ICRF), r_icrf (3,) km the attractor from the figure."""
    r, pole = mat_t_vec3(rot, r_icrf), mat_t_vec3(rot, pole_icrf)
    force = -matvec3(rot, _energy_gradient(inertia, r, pole, gm_j2_r2, False))
    reaction = matvec3(rot, -cross3(pole, _energy_gradient(inertia, r, pole, gm_j2_r2, True)))
    return figure_torque(inertia, r, pole, gm_j2_r2), force, reaction


def oblate_attractor(name, context, gm_j2_r2, pole_table, term_name):
    """A figure_figure Term for attractor ``name`` with GM J2 R^2 (km^5/d^2) and its pole table."""
    grid, samples = pole_table
    params = (context.index(name, term_name), float(gm_j2_r2), np.asarray(grid, dtype=float),
              np.ascontiguousarray(samples, dtype=float))
    return Term(term_name, torque, params, force, "Folkner et al. 2014 (IPN PR 42-196), N_figM-figE")


def build(context):
    """The Earth's J2 (the DE421 header's J2E at RE) with its pole from ``context.poles["earth"]``."""
    gm, h = context.gm[context.index("earth", "earth_j2")], header()
    return oblate_attractor("earth", context, gm * h["J2E"] * h["RE"] ** 2, context.poles["earth"], "earth_j2")
