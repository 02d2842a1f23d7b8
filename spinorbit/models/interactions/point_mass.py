"""Point masses on a degree-2 figure: Euler's *Theoria motus* ch. 16, Problem 91 (§815) and §818.

Torque of a mass GM at r (body axes) on a figure of inertia I:  N = 3 GM / r^5  r x (I r).
The figure's pull on the mass, to the same (second) order in size/r, from MacCullagh's
potential U_2 = -G (r^2 tr I - 3 r.I r) / (2 r^5) per unit mass (§818 gives its opposite,
the force on the figure's centre):

    F = GM [ (tr I r - 3 I r) / r^5 - 5/2 (r^2 tr I - 3 r.I r) r / r^7 ]

so that r x F = -N: the torque on the figure is the reaction of the moment of F; the interaction
energy is GM U_2 (:func:`energy`), and F = -grad_r of it.  Units: I G-scaled (km^5/d^2), GM km^3/d^2.
"""
from dataclasses import dataclass

import numpy as np
from numba import njit

from ...base.linker import cached
from ...base.rotations import cross3, dot3, mat_t_vec3, matvec3
from .base import Interaction, needs_forces


@njit(cache=True, nogil=True)
def anisotropic(inertia):
    """I - I_zz 1: the same torques and forces (an isotropic part exerts none), without the
    cancellation of r x (I r) for a nearly spherical body (the subtraction is exact, Sterbenz)."""
    out = inertia.copy()
    for i in range(3):
        out[i, i] -= inertia[2, 2]
    return out


@cached(nogil=True)
def torque(rot, inertia, rows, gm):
    """Sum over the masses at ``rows`` (n, 3, inertial, from the figure) of 3 GM/r^5 r x (I r), body axes (§815)."""
    inertia = anisotropic(inertia)
    total = np.zeros(3)
    for i in range(gm.shape[0]):
        r = mat_t_vec3(rot, rows[i])
        r2 = dot3(r, r)
        total += 3.0 * gm[i] / (r2 * r2 * np.sqrt(r2)) * cross3(r, matvec3(inertia, r))
    return total


@cached(nogil=True)
def force(rot, inertia, rows, gm):
    """The figure's degree-2 force on each mass (n, 3), inertial axes (§818)."""
    out = np.zeros((gm.shape[0], 3))
    inertia = anisotropic(inertia)
    trace = inertia[0, 0] + inertia[1, 1] + inertia[2, 2]
    for i in range(gm.shape[0]):
        r = mat_t_vec3(rot, rows[i])
        r2 = dot3(r, r)
        ir = matvec3(inertia, r)
        f = gm[i] * ((trace * r - 3.0 * ir) / (r2 * r2 * np.sqrt(r2))
                     - 2.5 * (r2 * trace - 3.0 * dot3(r, ir)) * r / (r2 * r2 * r2 * np.sqrt(r2)))
        out[i] = matvec3(rot, f)
    return out


@cached(nogil=True)
def energy(rot, inertia, rows, gm):
    """MacCullagh's interaction energy, sum over the masses of -GM (r^2 tr I - 3 r.I r) / (2 r^5)."""
    inertia = anisotropic(inertia)             # the isotropic part cancels in r^2 tr I - 3 r.I r
    trace = inertia[0, 0] + inertia[1, 1] + inertia[2, 2]
    total = 0.0
    for i in range(gm.shape[0]):
        r = mat_t_vec3(rot, rows[i])
        r2 = dot3(r, r)
        total -= 0.5 * gm[i] * (r2 * trace - 3.0 * dot3(r, matvec3(inertia, r))) / (r2 * r2 * np.sqrt(r2))
    return total


@cached(nogil=True)
def reaction(rot, rows, pulls):
    """(force on the figure's centre (inertial), torque on the figure (body axes)) from its pulls (n, 3) on
    the masses at ``rows``: minus their sum and minus their moments about its centre (§818)."""
    total, moment = np.zeros(3), np.zeros(3)
    for i in range(pulls.shape[0]):
        total -= pulls[i]
        moment -= cross3(rows[i], pulls[i])
    return total, mat_t_vec3(rot, moment)


def act(code, figure, attractors, rows, torque_call, force_call):
    """Emit a figure term's action: its torque alone where no centre is integrated, else its pulls on the
    attractors, the reaction on the figure's centre and the torque as the pulls' moment."""
    if not needs_forces(code, figure, attractors):
        code.add_torque(figure, torque_call)
        return
    pulls, on_figure, turning = code.local("pulls"), code.local("on_figure"), code.local("turning")
    code.line(f"{pulls} = {force_call}")
    code.line(f"{on_figure}, {turning} = {code.bind(reaction)}({code.rot(figure)}, {rows}, {pulls})")
    for k, body in enumerate(attractors):
        code.add_force(body, f"{pulls}[{k}]")
    code.add_force(figure, on_figure)
    code.add_torque(figure, turning)


@dataclass(frozen=True)
class PointMass(Interaction):
    """``attractors`` as point masses on ``figure``'s degree-2 figure (its inertia)."""

    figure: str
    attractors: tuple
    citation = "Euler, Theoria motus ch. 16 P91 (§815), §818"

    def bodies(self):
        return (self.figure, *self.attractors)

    def tidal_attractors(self, name):
        """Its attractors on ``figure`` (their tidal tensor is its torque); none on the attractors themselves."""
        return self.attractors if name == self.figure else ()

    def emit(self, code):
        rows, gm = code.rows(self.figure, self.attractors)
        args = f"({code.rot(self.figure)}, {code.inertia(self.figure)}, {rows}, {gm})"
        act(code, self.figure, self.attractors, rows, f"{code.bind(torque, 'point_mass_torque')}{args}",
            f"{code.bind(force, 'point_mass_force')}{args}")

    def energy(self, code):
        rows, gm = code.rows(self.figure, self.attractors)
        kernel = code.bind(energy, "point_mass_energy")
        return f"{kernel}({code.rot(self.figure)}, {code.inertia(self.figure)}, {rows}, {gm})"
