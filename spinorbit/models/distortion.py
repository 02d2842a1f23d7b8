"""The tidal and rotational distortion of a body's inertia (the Moon's, as DE421 models it).

Folkner et al. 2014 (IPN PR 42-196, §III, moments of inertia (36)-(41)); I_m as in Pavlov, Williams &
Suvorkin 2016 (CMDA 126:61, eq. 15) with the zz element corrected in Pavlov & Williams 2019
(doi:10.1007/s10569-019-9939-8):

    delta I = - k2 GM_E R^5 / r^5 [x_i x_j - r^2 d_ij / 3]
              + k2 R^5 / 3 [w_i w_j - d_ij (w^2 - n^2)/3,  zz: w_z^2 - (w^2 + 2 n^2)/3]

in G-scaled units (G I, km^5/d^2): x = the raiser's (the Earth's) position in the body's axes at t - tau (the
tide raised a time tau earlier, carried round with the body), w the body's angular velocity at t, n its mean
motion.  The torques then act with the distorted I; the rate of the tidal part enters Euler's equations
(the rotational part's rate, w varying by 1e-4 of n, is below 1e-12 of I per day and is left out).

Where the raiser was a time tau ago comes from the System's motion: read from an ephemeris, or, for a body
in the state, from its position, velocity, acceleration and two-body jerk (:func:`taylor_back`).
"""
import math

import numpy as np

from ..base.linker import cached
from ..base.rotations import cross3, dot3, mat_t_vec3

DIFFERENCE_D = 1e-3        # days, central difference of an ephemeris position for the raiser's velocity


@cached(nogil=True)
def rotate_about(v, axis, angle):
    """Rodrigues: v rotated right-handedly by ``angle`` about the unit vector ``axis``."""
    c, s = math.cos(angle), math.sin(angle)
    return v * c + cross3(axis, v) * s + axis * dot3(axis, v) * (1.0 - c)


@cached(nogil=True)
def delayed_in_body(rot, omega, x, v, tau):
    """The raiser's position x (km) and velocity v (km/d), ICRF, at t - tau, seen in the body axes of t - tau
    (carried round with the body by w tau): (r_del, v_del), the rate relative to the body."""
    wn = math.sqrt(dot3(omega, omega))
    axis = omega / wn
    r_del = rotate_about(mat_t_vec3(rot, x), axis, wn * tau)
    return r_del, rotate_about(mat_t_vec3(rot, v), axis, wn * tau) - cross3(omega, r_del)


@cached(nogil=True)
def taylor_back(r, v, acc, gm_pair, tau):
    """(position, velocity) a time tau earlier of a body at r (km) moving at v (km/d) with acceleration ``acc``
    (km/d^2) about a centre of GM ``gm_pair``: to third order in tau with the two-body jerk (16 m from DE421's
    delayed lunar position over a month; to second order with the two-body acceleration alone, 2 km)."""
    r2 = dot3(r, r)
    jerk = -gm_pair / (r2 * np.sqrt(r2)) * (v - 3.0 * dot3(r, v) / r2 * r)
    return (r - tau * v + 0.5 * tau * tau * acc - tau * tau * tau / 6.0 * jerk,
            v - tau * acc + 0.5 * tau * tau * jerk)


@cached(nogil=True)
def distortion(omega, r_del, v_del, tide, spin, n_mean):
    """(delta I, its rate), body axes, G-scaled: ``tide`` = k2 GM_E R^5, ``spin`` = k2 R^5 / 3 (km^5), n_mean the
    mean motion (rad/d); r_del, v_del the raiser in body axes at t - tau and its rate (module docstring)."""
    r2 = dot3(r_del, r_del)
    f = tide / (r2 * r2 * math.sqrt(r2))
    rv = dot3(r_del, v_del)
    w2, n2 = dot3(omega, omega), n_mean * n_mean
    delta, delta_rate = np.empty((3, 3)), np.empty((3, 3))
    for i in range(3):
        for j in range(3):
            d_ij = 1.0 if i == j else 0.0
            xx = r_del[i] * r_del[j]
            xx_rate = v_del[i] * r_del[j] + r_del[i] * v_del[j]
            delta_rate[i, j] = -f * (xx_rate - 2.0 * rv / 3.0 * d_ij) + 5.0 * f * rv / r2 * (xx - r2 / 3.0 * d_ij)
            rot = omega[i] * omega[j] - (w2 - n2) / 3.0 * d_ij
            if i == 2 and j == 2:
                rot = omega[2] * omega[2] - (w2 + 2.0 * n2) / 3.0
            delta[i, j] = -f * (xx - r2 / 3.0 * d_ij) + spin * rot
    return delta, delta_rate
