"""Gravity-gradient torque of Euler's *Theoria motus* ch. 16, Problem 91, and the §818 force.

All functions are numba-compiled.  Units: ``r_body`` in km (any length unit),
``gm`` in km^3/day^2, moments in any unit; the torque then comes out in
[moment unit] rad/day^2, ready for Euler's equations I dw/dt = N - w x I w.
"""
import math

import numpy as np
from numba import njit


@njit(cache=True)
def point_mass_torque(moments, r_body, gm):
    """Torque N = 3 GM / s^3 * u x (I u) of a point mass (Euler ch. 16 P91, §815).

    ``moments`` = (A, B, C) principal moments; ``r_body`` = position of the
    attracting mass from the body's centre of mass, in body principal axes.
    Component form (Euler's P, Q, R): N_x = 3 GM (C - B) u_y u_z / s^3, and cyclic.
    Valid to order 1/s^3; the neglected remainder is O(size/s) smaller (§816).
    """
    s2 = r_body[0] ** 2 + r_body[1] ** 2 + r_body[2] ** 2
    k = 3.0 * gm / (s2 * s2 * math.sqrt(s2))          # 3 GM / s^5, so u u -> r r
    a, b, c = moments[0], moments[1], moments[2]
    x, y, z = r_body[0], r_body[1], r_body[2]
    return np.array([k * (c - b) * y * z, k * (a - c) * z * x, k * (b - a) * x * y])


@njit(cache=True)
def point_masses_torque(moments, r_body_all, gm_all):
    """Sum of point_mass_torque over rows of ``r_body_all`` (n, 3) with ``gm_all`` (n,)."""
    total = np.zeros(3)
    for i in range(gm_all.shape[0]):
        total += point_mass_torque(moments, r_body_all[i], gm_all[i])
    return total


@njit(cache=True)
def figure_force(moments, mass, r_body, gm):
    """Force on the body's centre from a point mass GM at r_body, to order 1/s^4 (§818).

    Returns the force divided by G (units of [mass] GM / km^2 / G -> pass gm = G m
    and mass = M to get GM M / s^2 in km^3/day^2 x mass unit / km^2).  In Euler's
    form: F = GM [ (M/s^2 + 3 (tr I - 5 u.Iu)/(2 s^4)) u + 3 I u / s^4 ], pointing
    from the body towards the mass; the second-order part is the figure's
    back-reaction on the orbit.
    """
    s = math.sqrt(r_body[0] ** 2 + r_body[1] ** 2 + r_body[2] ** 2)
    u = r_body / s
    iu = moments * u
    trace = moments[0] + moments[1] + moments[2]
    radial = mass / s**2 + 1.5 * (trace - 5.0 * (u[0] * iu[0] + u[1] * iu[1] + u[2] * iu[2])) / s**4
    return gm * (radial * u + 3.0 * iu / s**4)
