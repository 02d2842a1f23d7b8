"""The lunar model (layer 2): figure torques of degree 2-4, fluid core, tidal and rotational distortion.

Four levels, each adding physics to the one before:

1. Euler's model: a rigid degree-2 Moon, Earth and Sun as point masses
   (Euler ch. 16 P91, §815: N = 3 GM/r^5 r x I r);
2. + the Moon's degree-3 and degree-4 gravity field acting with every point mass:
   N = -M_A r x grad U_Moon(r) (Williams, Boggs & Folkner 2008; Folkner et al. 2014);
3. + a fluid core with an oblate core-mantle boundary, coupled by friction and by the
   fluid's pressure on the boundary; the tidal and rotational distortion of the mantle's
   moment of inertia; and the Earth's J2 acting on the Moon's degree-2 figure
   (Folkner et al. 2014, IPN PR 42-196, §III "Lunar orientation": mantle and core
   equations (34)-(35), moments of inertia (36)-(41), point-mass torque (43), figure-
   figure torque (44), equation numbers as cited by PlanetaryEphemeris.jl; I_m as in
   Pavlov, Williams & Suvorkin 2016, CMDA 126:61, eq. (15) with the zz element
   corrected in Pavlov & Williams 2019, doi:10.1007/s10569-019-9939-8):

   I_m = I~ - I_c - k2 (M_E/M) (R^3/r^5) [x_i x_j - r^2 d_ij/3]
               + k2 R^3/(3 GM) [w_i w_j - d_ij (w^2 - n^2)/3, zz: w_z^2 - (w^2 + 2 n^2)/3]
   I_c = diag(A_c, A_c, C_c),  A_c = C_c (1 - f_c)
   d(I_m w_m)/dt + w_m x I_m w_m = N_figure + N_figM-figE + N_cmb
   N_cmb = k_v (w_c - w_m) + (C_c - A_c) (z . w_c) (z x w_c)
   I_c dw_c/dt + w_m x I_c w_c = -N_cmb                 (w_c in mantle axes, z = (0, 0, 1))
   N_figM-figE = 15 GM_E J2E R_E^2 / (2 r^5) [(1 - 7 s^2) u x I u
                 + 2 s (u x I p + p x I u) - (2/5) p x I p]   (u = r/r, p = Earth pole, s = u.p)

   x = the Earth's position in the mantle frame at t - tau (the tide raised a time
   tau earlier, carried round with the mantle); w in the rotational term is taken at t.
   The torques act with the whole Moon's distorted I; the mantle turns with I - I_c.

   What limited the pole (measured against DE421 over 1900-2050, benchmarks/RESULTS.md):
   DE421's core is oblate (header COBLAT, f_c = 3.8e-4).  Its pressure torque couples
   the core's free precession (~200 yr) to the mantle; with a spherical core the pole
   is off by 1.24" (0.82" rms), with the oblate core and the Earth's J2 (0.16" alone)
   by 0.0036" (0.0021" rms), longitude 0.0005".  From DE421's own epoch (JDEPOC,
   where the header gives the core state) to 2050: 0.003".  The published forms
   matter: the uncorrected zz element (w^2 - n^2) or leaving out dI/dt w moves the
   pole by 3.3"; the rotational term as a whole by 0.07".
4. (optional) further point masses (planets) acting on the figure.

The torques of the levels are terms (spinorbit.terms: point_mass, harmonics, earth_j2, and any
other named in the scenario), fused into one kernel; this module adds what is the Moon's own:
the fluid core and the distortion of the mantle's inertia.

Units: km, rad/day, GM km^3/day^2, moments in units of M R^2 (R = gravity reference
radius).  State y = [q (4), w_m (3)] or [q, w_m, w_c (3)] with a core.
"""
import math
from dataclasses import dataclass

import numpy as np
from numba import njit

from .dynamics import SpinSystem, make_figure_torque
from .linker import free, link, template
from .rotations import cross3, diag3, dot3, mat_t_vec3, matrix_from_quat, matvec3, put, quat_rate, solve3
from .terms.base import fuse

positions, terms, WITH_CORE, WITH_TIDES = free("positions", "terms", "WITH_CORE", "WITH_TIDES")    # bound by link()

# Layout of the float vector ``consts`` in the parameters (see moon_params).
R_KM, K2_MASS_RATIO, K2_ROT, TAU_D, KV, C_CORE, N_MEAN, F_CORE = range(8)

@dataclass(frozen=True)
class Level:
    """A level of the lunar model: its terms (spinorbit.terms), the Moon's own physics, the attracting bodies."""

    name: str
    terms: tuple
    core: bool = False
    tides: bool = False
    bodies: tuple = ("earth", "sun")


LEVELS = {1: Level("Euler: degree-2 Moon, Earth + Sun point masses", ("point_mass",)),
          2: Level("+ Moon degree 3 and 4", ("point_mass", "harmonics")),
          3: Level("+ oblate fluid core, tidal and rotational distortion, Earth's J2 on the figure",
                   ("point_mass", "harmonics", "earth_j2"), core=True, tides=True),
          4: Level("+ Venus, Mars, Jupiter, Saturn on the figure", ("point_mass", "harmonics", "earth_j2"), core=True,
                   tides=True, bodies=("earth", "sun", "venus", "jupiter", "mars", "saturn"))}
N_MEAN_RAD_D = 2 * math.pi / 27.321661                      # sidereal month, rad/day


@njit(cache=True)
def rotate_about(v, axis, angle):
    """Rodrigues: v rotated right-handedly by ``angle`` about the unit vector ``axis``."""
    c, s = math.cos(angle), math.sin(angle)
    return v * c + cross3(axis, v) * s + axis * dot3(axis, v) * (1.0 - c)


@njit(cache=True)
def distortion(omega, r_del, v_del, consts):
    """Tidal + rotational change of the mantle inertia (M R^2) and its rate (tidal part), body axes.

    r_del, v_del: the Earth's position (km) and its rate of change in mantle axes (km/d)
    at t - tau.  The rotational part's rate (w varies by 1e-4 of n) is below 1e-12 M R^2/d
    and is left out.
    """
    k_tide = consts[K2_MASS_RATIO] * consts[R_KM] ** 3
    r2 = dot3(r_del, r_del)
    f = k_tide / (r2 * r2 * math.sqrt(r2))
    rv = dot3(r_del, v_del)
    w2, n2 = dot3(omega, omega), consts[N_MEAN] ** 2
    delta, delta_rate = np.empty((3, 3)), np.empty((3, 3))
    for i in range(3):                     # the module docstring's I_m terms, element (i, j)
        for j in range(3):
            d_ij = 1.0 if i == j else 0.0
            xx = r_del[i] * r_del[j]
            xx_rate = v_del[i] * r_del[j] + r_del[i] * v_del[j]
            tide = -f * (xx - r2 / 3.0 * d_ij)
            delta_rate[i, j] = -f * (xx_rate - 2.0 * rv / 3.0 * d_ij) + 5.0 * f * rv / r2 * (xx - r2 / 3.0 * d_ij)
            rot = omega[i] * omega[j] - (w2 - n2) / 3.0 * d_ij
            if i == 2 and j == 2:
                rot = omega[2] * omega[2] - (w2 + 2.0 * n2) / 3.0
            delta[i, j] = tide + consts[K2_ROT] * rot
    return delta, delta_rate


@njit(cache=True)
def delayed_in_mantle(rot, omega, x, v, tau):
    """The Earth's position x (km) and velocity v (km/d), ICRF, at t - tau, seen in the mantle axes of t - tau
    (carried round with the mantle by w tau): (r_del, v_del), the rate relative to the mantle."""
    wn = math.sqrt(dot3(omega, omega))
    axis = omega / wn
    r_del = rotate_about(mat_t_vec3(rot, x), axis, wn * tau)
    return r_del, rotate_about(mat_t_vec3(rot, v), axis, wn * tau) - cross3(omega, r_del)


_DT_DIFF = 1e-3        # days, central difference for the Earth's velocity at t - tau


@template("positions", "terms", "WITH_CORE", "WITH_TIDES")
def moon_rhs(t, y, p):
    """dy/dt of the lunar model; y = [q, w_m] or [q, w_m, w_c]; p = moon_params(...)."""
    moments, gm, data, term_params, consts = p
    q, omega = y[:4], y[4:7]
    rot = matrix_from_quat(q)                 # body -> ICRF; mat_t_vec3(rot, v) takes v to body axes
    inertia = diag3(moments)
    inertia_rate = np.zeros((3, 3))
    if WITH_TIDES:
        tau = consts[TAU_D]
        vel_i = (positions(t - tau + _DT_DIFF, data)[0] - positions(t - tau - _DT_DIFF, data)[0]) / (2 * _DT_DIFF)
        r_del, v_del = delayed_in_mantle(rot, omega, positions(t - tau, data)[0], vel_i, tau)
        delta, inertia_rate = distortion(omega, r_del, v_del, consts)
        inertia = inertia + delta
    torque = terms(t, y, rot, inertia, positions(t, data), gm, term_params)
    dy = np.empty_like(y)
    put(dy[:4], quat_rate(q, omega))
    if WITH_CORE:
        mantle_rate, core_rate = mantle_and_core_rates(omega, y[7:10], inertia, inertia_rate, torque, consts)
        put(dy[7:10], core_rate)
    else:
        mantle_rate = solve3(inertia, torque - cross3(omega, matvec3(inertia, omega)) - matvec3(inertia_rate, omega))
    put(dy[4:7], mantle_rate)
    return dy


@njit(cache=True)
def mantle_and_core_rates(omega, omega_c, inertia, inertia_rate, torque, consts):
    """(dw_m/dt, dw_c/dt), rad/d^2, mantle axes: the torque (M R^2 rad/d^2) acts with the whole Moon's I
    (M R^2, with its distortion and rate); the mantle turns with I - I_c, the core by the boundary's torque."""
    c_core = consts[C_CORE]
    core_moments = np.array([c_core * (1.0 - consts[F_CORE]), c_core * (1.0 - consts[F_CORE]), c_core])
    inertia = inertia - diag3(core_moments)
    n_cmb = consts[KV] * (omega_c - omega) + (c_core - core_moments[0]) * omega_c[2] * np.array(
        [-omega_c[1], omega_c[0], 0.0])
    torque = torque + n_cmb
    core_rate = (-cross3(omega, core_moments * omega_c) - n_cmb) / core_moments
    rhs_vec = torque - cross3(omega, matvec3(inertia, omega)) - matvec3(inertia_rate, omega)
    return solve3(inertia, rhs_vec), core_rate


def make_moon_rhs(positions, terms, core=False, tides=False):
    """Compiled rhs(t, y, p) of the lunar model.

    ``positions(t, data) -> (n, 3)``: attracting bodies relative to the Moon, km, ICRF;
    body 0 must be the Earth (it raises the tide).  ``terms``: the fused torque of the
    model's terms (terms.base.fuse); ``core``: fluid core, y has 10 components;
    ``tides``: tidal and rotational distortion.  p = moon_params(...).
    """
    return link(moon_rhs, positions=positions, terms=terms, WITH_CORE=bool(core), WITH_TIDES=bool(tides))


def moon_params(moon, gm, data, term_params, n_mean=N_MEAN_RAD_D):
    """Parameter tuple of make_moon_rhs: (moments, gm (n,), data, term_params, consts).

    ``moon``: a bodies.moon.Moon (moments in M R^2, R = radius_km; k2, tau_d days; kv_over_c 1/day;
    core C_c/C and flattening); gm (n,) km^3/d^2, gm[0] = the Earth's; data: the orbit kernel's
    data; n_mean: mean motion, rad/day (the rotational distortion's reference).
    """
    c_total = moon.moments[2]
    consts = np.zeros(8)
    consts[R_KM] = moon.radius_km
    consts[K2_MASS_RATIO] = moon.k2 * gm[0] / moon.gm_km3_d2
    consts[K2_ROT] = moon.k2 * moon.radius_km**3 / (3.0 * moon.gm_km3_d2)
    consts[TAU_D] = moon.tau_d
    consts[KV] = moon.kv_over_c_per_d * c_total
    consts[C_CORE] = moon.core_c_over_c * c_total
    consts[N_MEAN] = n_mean
    consts[F_CORE] = moon.core_flattening
    return (np.asarray(moon.moments, dtype=float), np.asarray(gm, dtype=float), data, term_params, consts)


def moon_system(moon, orbits, terms, t0, y0, core=False, tides=False, name="moon"):
    """SpinSystem of the lunar model: ``terms`` (a tuple of terms.base.Term) on the Moon ``moon``,
    driven by ``orbits`` (kernel, gm, data; body 0 the Earth); y0 = [q, w_m] (+ w_c with a core).

    Without core and distortion the Moon is one rigid body under an external torque, which
    splitting methods take (system.torque); with them no separable torque exists.
    """
    kernel, term_params = fuse(terms)
    params = moon_params(moon, orbits.gm, orbits.data, term_params)
    rhs = make_moon_rhs(orbits.kernel, kernel, core, tides)
    torque = None if (core or tides) else make_figure_torque(orbits.kernel, kernel)
    return SpinSystem(rhs, params, t0, y0, moon.moments, torque, name)
