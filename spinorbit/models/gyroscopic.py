"""The gyroscopic rotator: an axisymmetric body whose state is its spin angular momentum l (inertial axes).

Only l moves, dl/dt = N + Omega x l (Omega the rate of the frame the equations hold in, e.g. the geodesic
precession): the free nutation of a day's period is left out, so the step follows the month, not the day.
The torques act on the figure axis z, which on the forced (slow) solution leads the unit vector ell = l/|l|
by the Oppolzer terms: for dz/dt = (L x z)/A exactly (A = B),

    z = ell - (ell x ell')/lam - ell''_perp/lam^2 + ell x ell'''/lam^3 + O(lam^-4),   lam = |l|/A,
    ell' = N_perp/|l|,  ell''_perp = N'_perp/|l|,  ell''' = N''_perp/|l|,

with N the point masses' degree-2 torque (C - A)(T ell) x ell from their tidal tensor T = 3 sum GM r r^T / r^5
(Euler ch. 16 P91, §815, summed over the masses; Oppolzer's terms, Woolard 1953; each order follows from the
last by dz/dt = lam ell x z on the slow solution).  The right-hand side takes z to first order (the second moves
the torque by 4e-10 of itself); the figure axes reported take three orders (the third moves the Earth's
13.66-d nutation by 0.1 mas: (nu/lam)^3 of it, nu its frequency; models.start.oppolzer_axes).
"""
import math

import numpy as np
from numba import njit

from ..base.linker import cached
from ..base.rotations import cross3, dot3, matvec3


@cached(nogil=True)
def frame_from_axis(z):
    """A rotation matrix whose third column is the unit vector z (its x axis: e_x made normal to z)."""
    x = np.array([1.0, 0.0, 0.0]) - z[0] * z
    x = x / np.sqrt(dot3(x, x))
    y = cross3(z, x)
    m = np.empty((3, 3))
    for i in range(3):
        m[i, 0], m[i, 1], m[i, 2] = x[i], y[i], z[i]
    return m


@njit(cache=True, nogil=True)
def tidal_tensor(rows, gm):
    """3 sum GM r r^T / r^5 (1/d^2) of the point masses at ``rows`` (n, 3) km with GM ``gm`` (n,) km^3/d^2."""
    out = np.zeros((3, 3))
    for i in range(gm.shape[0]):
        r = rows[i]
        s2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2]
        k = 3.0 * gm[i] / (s2 * s2 * math.sqrt(s2))
        for a in range(3):
            for b in range(3):
                out[a, b] += k * r[a] * r[b]
    return out


@cached(nogil=True)
def figure_axis(spin, tensor, a, c_minus_a):
    """The figure axis to first order in 1/lam from the spin angular momentum ``spin`` (inertial), the point
    masses' tidal tensor, the equatorial moment A and C - A (module docstring)."""
    norm = math.sqrt(dot3(spin, spin))
    ell = spin / norm
    n0 = c_minus_a * cross3(matvec3(tensor, ell), ell) / (norm * norm / a)
    z = ell - cross3(ell, n0)
    return z / math.sqrt(dot3(z, z))
