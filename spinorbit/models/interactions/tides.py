"""The Earth's tides on the Moon's orbit, as JPL's DE421/DE430 model them (Folkner et al. 2014,
IPN PR 42-196, the tidal acceleration of the Moon, eq. 32).

A body T (the Moon, the Sun) at x from the Earth raises a degree-2 tide on the Earth.  Its band m
(0 zonal, 1 diurnal, 2 semi-diurnal) has a Love number k2m and a time delay tau_m, and answers to T
where it was tau_m ago, seen from the Earth as it was then (one delay per band, the DE421 model;
Chapront, Chapront-Touze & Francou 2002, A&A 387, 700, §8: the band's argument is m(alpha - alpha* -
omega tau)):

    s_m = Rot(p, |w| tau_m) x(t - tau_m)         (right-handed about the pole p = w/|w|; w the spin)

(the zonal tide is axisymmetric: its rotation drops out).  With z = r.p along the pole and rho the
equatorial part of r (z*, rho* those of s_m), the tide's potential outside the Earth is

    U_m(r) = k2m GM_T R_E^5 A_m(r, s_m) / (2 r^5 s_m^5),
    A_0 = (2 z^2 - rho^2)(2 z*^2 - rho*^2) / 2,   A_1 = 6 z z* rho.rho*,
    A_2 = 3 (rho.rho*)^2 - 3/2 rho^2 rho*^2,

the addition theorem for the static Love-number potential k2 GM_T R_E^5 (3 (r.s)^2 - r^2 s^2) / (2 r^5 s^5)
(= A_0 + A_1 + A_2) split by order m.  The Moon feels GM_M grad U and the Earth the opposite, so the
Moon's acceleration relative to the Earth is (Folkner et al. 2014, eq. 32, vector form)

    a = (1 + GM_M/GM_E) sum_T sum_m k2m GM_T R_E^5 / (2 r^5 s_m^5) [2 Q_m r - 5 A_m r / r^2],
    A_m = r.Q_m r:  Q_0 r = (2 z*^2 - rho*^2)(2 z p - rho)/2,  Q_1 r = 3 z* (z rho* + (rho*.rho) p),
                    Q_2 r = 3 (rho*.rho) rho* - 3/2 rho*^2 rho.

The delayed position is x - tau u - tau^2/2 GM x/|x|^3 (the two-body motion to second order in tau,
u = dx/dt); the rotation by |w| tau (<= 0.07 rad) is exact.  Against DE421's own delayed positions
(one year, 2000) this is off by <= 1.8e-6 |x| in the Moon's zonal band (n tau_0 = 0.015; first order
alone: 1.3e-4), <= 4e-8 |x| in its diurnal and semi-diurnal bands and <= 4e-9 |x| for the Sun (the
neglected (n tau)^3/6 and the Sun's pull on the Moon during tau), on a tidal acceleration that is
itself ~1e-11 of the Earth's pull.  (DE430 splits each delay into an orbital and a rotational one;
DE421's header has one per band, used for both.)

The reaction: both bulges are the Earth's, and the Moon pulls on them with -GM_M grad U (through the
Earth's centre) and the torque -r x (GM_M grad U) about it, so the orbit's angular momentum
mu r x v (mu = GM_E GM_M/(GM_E + GM_M), G-scaled) and the Earth's spin exchange
mu r x a = -torque_on_earth and their sum is conserved; this holds alike for the Sun-raised bulge.
Not here: the Sun's own pull on both bulges (a torque on the Earth and a force on the Earth-Moon
barycentre that DE421's eq. 32 leaves out).

Units: km, d, GM in km^3/d^2, angular rates rad/d, torques G-scaled (km^5/d^4); frame ICRF.
"""
import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from ...base.linker import cached
from ...base.rotations import cross3, dot3
from .base import Interaction

GM_E, GM_M, GM_S, RADIUS, K2, TAU = 0, 1, 2, 3, 4, 7     # offsets in the parameters


@njit(cache=True, nogil=True)
def delayed(x, u, gm, pole, rate, tau, band):
    """s_m: a body at x (km) moving at u (km/d) about the Earth with GM (km^3/d^2), where it was tau (d)
    ago, rotated by rate tau (rad) about the unit pole (bands 1, 2); ICRF, km.  (Written out by component:
    this runs six times per rhs.)"""
    x2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2]
    f = 0.5 * tau * tau * gm / (x2 * math.sqrt(x2))
    b0, b1, b2 = x[0] - tau * u[0] - f * x[0], x[1] - tau * u[1] - f * x[1], x[2] - tau * u[2] - f * x[2]
    out = np.empty(3)
    if band == 0:
        out[0], out[1], out[2] = b0, b1, b2
        return out
    c, s = math.cos(rate * tau), math.sin(rate * tau)
    d = (1.0 - c) * (pole[0] * b0 + pole[1] * b1 + pole[2] * b2)
    out[0] = c * b0 + s * (pole[1] * b2 - pole[2] * b1) + d * pole[0]
    out[1] = c * b1 + s * (pole[2] * b0 - pole[0] * b2) + d * pole[1]
    out[2] = c * b2 + s * (pole[0] * b1 - pole[1] * b0) + d * pole[2]
    return out


@cached(nogil=True)
def band_gradient(r, s, pole, band):
    """grad_r [A_m(r, s) / (r^5 s^5)] at r (km) for the tide of band m raised from s (km), 1/km^5."""
    z, zs = dot3(r, pole), dot3(s, pole)
    rho0, rho1, rho2 = r[0] - z * pole[0], r[1] - z * pole[1], r[2] - z * pole[2]
    rhos0, rhos1, rhos2 = s[0] - zs * pole[0], s[1] - zs * pole[1], s[2] - zs * pole[2]
    rhos_rho, rhos2_ = rhos0 * rho0 + rhos1 * rho1 + rhos2 * rho2, rhos0 * rhos0 + rhos1 * rhos1 + rhos2 * rhos2
    if band == 0:
        f = 0.5 * (2.0 * zs * zs - rhos2_)
        q0, q1, q2 = f * (2.0 * z * pole[0] - rho0), f * (2.0 * z * pole[1] - rho1), f * (2.0 * z * pole[2] - rho2)
    elif band == 1:
        f = 3.0 * zs
        q0, q1, q2 = f * (z * rhos0 + rhos_rho * pole[0]), f * (z * rhos1 + rhos_rho * pole[1]), f * (
            z * rhos2 + rhos_rho * pole[2])
    else:
        f, g = 3.0 * rhos_rho, 1.5 * rhos2_
        q0, q1, q2 = f * rhos0 - g * rho0, f * rhos1 - g * rho1, f * rhos2 - g * rho2
    r2, s2 = dot3(r, r), dot3(s, s)
    rq = 5.0 * (r[0] * q0 + r[1] * q1 + r[2] * q2) / r2
    scale = 1.0 / (r2 * r2 * math.sqrt(r2) * s2 * s2 * math.sqrt(s2))
    out = np.empty(3)
    out[0] = (2.0 * q0 - rq * r[0]) * scale
    out[1] = (2.0 * q1 - rq * r[1]) * scale
    out[2] = (2.0 * q2 - rq * r[2]) * scale
    return out


@cached(nogil=True)
def raised_by(r, x, u, gm, gm_pair, spin, p):
    """The Moon's acceleration relative to the Earth (km/d^2, ICRF), at r, from the tide raised by a body
    of GM gm at x moving at u (its two-body GM with the Earth gm_pair); spin the Earth's (rad/d)."""
    rate = math.sqrt(dot3(spin, spin))
    pole = spin / rate
    total = np.zeros(3)
    for m in range(3):
        s = delayed(x, u, gm_pair, pole, rate, p[TAU + m], m)
        total += p[K2 + m] * band_gradient(r, s, pole, m)
    radius2 = p[RADIUS] * p[RADIUS]
    return (0.5 * (1.0 + p[GM_M] / p[GM_E]) * gm * radius2 * radius2 * p[RADIUS]) * total


@cached(nogil=True)
def acceleration(r, v, r_sun, v_sun, spin, p):
    """The Moon's acceleration relative to the Earth (km/d^2, ICRF) from the tides the Moon (at r, v) and
    the Sun (at r_sun, v_sun; km, km/d from the Earth) raise on the Earth of spin w (rad/d, ICRF)."""
    moon = raised_by(r, r, v, p[GM_M], p[GM_E] + p[GM_M], spin, p)
    return moon + raised_by(r, r_sun, v_sun, p[GM_S], p[GM_S] + p[GM_E] + p[GM_M], spin, p)


@cached(nogil=True)
def torque_on_earth(r, v, r_sun, v_sun, spin, p):
    """The Moon's torque on the Earth's tides, -mu r x a (G-scaled, km^5/d^4, ICRF): the orbit gains
    mu r x a of angular momentum, the Earth's spin loses as much."""
    return reaction(r, acceleration(r, v, r_sun, v_sun, spin, p), p)


@cached(nogil=True)
def reaction(r, a, p):
    """:func:`torque_on_earth` from the tidal acceleration ``a`` already computed at r."""
    mu = p[GM_E] * p[GM_M] / (p[GM_E] + p[GM_M])
    return -mu * cross3(r, a)


@dataclass(frozen=True)
class Tides(Interaction):
    """The tides raised on ``body`` (the Earth) by ``felt_by`` (the Moon, the pair's secondary) and by ``sun``,
    acting on the pair's relative orbit and, in reaction, on ``body``'s spin.  ``love`` = {band: (k2m, tau_m d)}
    and ``radius_km``; GMs from the System."""

    body: str
    felt_by: str
    sun: str
    love: tuple
    radius_km: float
    citation = "Folkner et al. 2014 (IPN PR 42-196), eq. 32; Chapront, Chapront-Touze & Francou 2002, §8"

    def bodies(self):
        return (self.body, self.felt_by, self.sun)

    def tidal_attractors(self, name):
        """None: the figure axis leaves out the torque of the tidal bulge (a delayed response, not the figure's)."""
        return ()

    def emit(self, code):
        motion = code.system.motion
        if (motion.primary, motion.secondary) != (self.body, self.felt_by):
            raise ValueError(f"tides on {self.body!r} felt by {self.felt_by!r} need the pair ({self.body}, "
                             f"{self.felt_by}) in the state")
        k2 = [k for k, _ in self.love]
        tau = [t for _, t in self.love]
        p = code.param(f"{self.body}_tides", np.array([motion.gm(self.body), motion.gm(self.felt_by),
                                                       motion.gm(self.sun), self.radius_km, *k2, *tau]))
        r, v = code.relative(self.body, self.felt_by), code.relative_velocity(self.body, self.felt_by)
        r_sun, v_sun = code.relative(self.body, self.sun), code.relative_velocity(self.body, self.sun)
        tide = code.local("tide")
        kernel = code.bind(acceleration, "tide_acceleration")
        code.line(f"{tide} = {kernel}({r}, {v}, {r_sun}, {v_sun}, {code.spin(self.body)}, {p})")
        motion.add_relative_acceleration(code, tide)
        code.add_torque(self.body, f"{code.bind(reaction, 'tide_reaction')}({r}, {tide}, {p})", "inertial")
