"""Point masses on a degree-2 figure: Euler's *Theoria motus* ch. 16, Problem 91 (§815) and §818.

Torque of a mass GM at r (body axes) on a figure of inertia I:  N = 3 GM / r^5  r x (I r).
The figure's pull on the mass, to the same (second) order in size/r, from MacCullagh's
potential U_2 = -G (r^2 tr I - 3 r.I r) / (2 r^5) per unit mass (§818 gives its opposite,
the force on the figure's centre):

    F = GM [ (tr I r - 3 I r) / r^5 - 5/2 (r^2 tr I - 3 r.I r) r / r^7 ]

so that r x F = -N: the torque on the figure is the reaction of the moment of F; the interaction
energy is GM U_2 (``energy``), and F = -grad_r of it.
"""
import numpy as np
from numba import njit

from ..rotations import cross3, dot3, mat_t_vec3, matvec3
from .base import Term, anisotropic


@njit(cache=True, nogil=True)
def torque(t, y, rot, inertia, r_icrf, gm, p):
    """Sum over the masses of 3 GM/r^5 r x (I r), body axes (§815)."""
    inertia = anisotropic(inertia)
    total = np.zeros(3)
    for i in range(gm.shape[0]):
        r = mat_t_vec3(rot, r_icrf[i])
        r2 = dot3(r, r)
        total += 3.0 * gm[i] / (r2 * r2 * np.sqrt(r2)) * cross3(r, matvec3(inertia, r))
    return total


@njit(cache=True, nogil=True)
def force(t, y, rot, inertia, r_icrf, gm, p):
    """The figure's degree-2 force on each mass (n, 3), ICRF, [inertia unit]/(km d^2) (§818)."""
    out = np.zeros((gm.shape[0], 3))
    inertia = anisotropic(inertia)
    trace = inertia[0, 0] + inertia[1, 1] + inertia[2, 2]
    for i in range(gm.shape[0]):
        r = mat_t_vec3(rot, r_icrf[i])
        r2 = dot3(r, r)
        ir = matvec3(inertia, r)
        f = gm[i] * ((trace * r - 3.0 * ir) / (r2 * r2 * np.sqrt(r2))
                     - 2.5 * (r2 * trace - 3.0 * dot3(r, ir)) * r / (r2 * r2 * r2 * np.sqrt(r2)))
        out[i] = matvec3(rot, f)
    return out


@njit(cache=True, nogil=True)
def energy(t, y, rot, inertia, r_icrf, gm, p):
    """MacCullagh's interaction energy, sum over the masses of -GM (r^2 tr I - 3 r.I r) / (2 r^5):
    [inertia unit]/d^2 (with GM in km^3/d^2, the energy times G over the figure's inertia unit)."""
    inertia = anisotropic(inertia)             # the isotropic part cancels in r^2 tr I - 3 r.I r
    trace = inertia[0, 0] + inertia[1, 1] + inertia[2, 2]
    total = 0.0
    for i in range(gm.shape[0]):
        r = mat_t_vec3(rot, r_icrf[i])
        r2 = dot3(r, r)
        total -= 0.5 * gm[i] * (r2 * trace - 3.0 * dot3(r, matvec3(inertia, r))) / (r2 * r2 * np.sqrt(r2))
    return total


def build(context):
    """Every attracting body of the orbit source as a point mass on the figure."""
    return Term("point_mass", torque, (), force, "Euler, Theoria motus ch. 16 P91 (§815), §818")
