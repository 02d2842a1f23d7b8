"""The Earth-Moon system in the solar system: the Moon's orbit, the Moon's mantle and core and the Earth's
spin in one state, coupled both ways; the Sun, the planets and the Earth-Moon barycentre from the ephemeris
(or a REBOUND run, :func:`sample_external`).

State (19,): ``y = [r (3), v (3), q (4), w_m (3), w_c (3), l (3)]``
- r, v: the Moon from the Earth, km and km/d, ICRF;
- q, w_m, w_c: the Moon's attitude (body -> ICRF) and its mantle's and fluid core's angular velocities
  (mantle axes, rad/d), the lunar model of spinorbit.moon level 3 (DE421's moments, field, core, tides);
- l: the Earth's spin angular momentum, G-scaled (G C w, km^5/d^3, ICRF).  The Earth is gyroscopic: its
  figure axis is taken along l (they differ by A/(C w) l x dl/dt/|l|, ~1e-8 rad), which leaves out the
  free nutation of a day's period and lets the step follow the month.  Axisymmetric: C - A = J2E M RE^2
  (the DE421 header's J2, as DE421 used it on the orbit) and C = (C - A)/H_d (IAU 2006's dynamical
  ellipticity, which sets the precession rate; C/(M RE^2) = 0.330694); J3, J4 as in coupled.

Forces on the relative orbit (each figure's torque with its reaction force, Euler §818; Folkner et al. 2014,
IPN PR 42-196):
- Newton: the Earth-Moon monopole and the direct and indirect pulls of the Sun and the planets (barycentres
  of their systems, DE421's GMs), with the Earth and the Moon placed about DE421's Earth-Moon barycentre;
- EIH: the 1PN point-mass correction of every body (spinorbit.relativity), the Moon's minus the Earth's;
- the figures of the Earth and the Moon on each other (coupled.figure_forces) and the Sun on both figures
  (the Moon's degrees 2-4, the Earth's degree 2), the reactions on the Sun dropped (it comes from DE421);
- the tides raised on the Earth by the Moon and the Sun (spinorbit.terms.earth_tides, DE421's K2E, TAUE),
  their torque on the Earth; the Moon's tidal and rotational distortion enters through its inertia.

The Earth's spin feels the Moon's and the Sun's torques, the tides' reaction, and the geodesic precession
(3/2) GM_sun / (c^2 |x|^3) x x w of the heliocentric Earth (x, w).  The planets' torques on the figures
(level 4) and the Sun's on the Earth's J3, J4 are left out (below 0.02"/cy in the Earth's precession).

Units: km, d, G-scaled masses (GM, km^3/d^2) and inertias (G I, km^5/d^2), so that forces are G times the
physical ones; the Moon's own equations (spinorbit.moon) keep its moments in M R^2.
"""
import numpy as np
from numba import njit

from . import coupled
from .bodies import earth
from .bodies.de421_header import gm_km3_d2, header
from .bodies.moon import de421
from .errors import InputError
from .moon import TAU_D, delayed_in_mantle, distortion, mantle_and_core_rates, moon_params
from .orbits.interpolant import hermite_states
from .relativity import accelerations as eih_accelerations, c_km_d
from .rotations import cross3, diag3, dot3, mat_t_vec3, matrix_from_quat, matvec3, put, quat_rate
from .terms import earth_tides, harmonics, point_mass

# The bodies read from the ephemeris (barycentric); the Earth and the Moon sit about the barycentre EMB.
EXTERNAL = ("sun", "mercury", "venus", "earth_moon_barycenter", "mars", "jupiter", "saturn", "uranus",
            "neptune", "pluto")
SUN, EMB = 0, 3
# What can be switched off: the flags of the parameters, in this order.
SWITCHES = ("relativity", "earth_tides", "moon_distortion", "geodesic", "planets")


def parameters(external_data, switches=SWITCHES):
    """p = (external data, gm (10,), figures (coupled.parameters, with the Earth's moments below), moon
    (consts, moments M R^2, G M R^2), the Earth's moments (A, A, C; G-scaled, km^5/d^2), tides, flags (5,),
    c km/d) for :func:`rhs`; ``switches``: the SWITCHES on."""
    unknown = sorted(set(switches) - set(SWITCHES))
    if unknown:
        raise InputError("switches", unknown, f"names from {list(SWITCHES)}")
    h, moon = header(), de421()
    gm_ext = np.array([0.0 if name == "earth_moon_barycenter" else gm_km3_d2(name) for name in EXTERNAL])
    figures = coupled.parameters()
    gm = figures[0]
    c_minus_a = h["J2E"] * gm[0] * h["RE"] ** 2
    c_e = c_minus_a / earth.H_D
    figures = (gm, figures[1], np.array([c_e - c_minus_a, c_e - c_minus_a, c_e]), *figures[3:])
    consts = moon_params(moon, gm, None, ())[4]
    moon_part = (consts, np.asarray(moon.moments, dtype=float), gm[1] * moon.radius_km ** 2)
    flags = np.array([1.0 if name in switches else 0.0 for name in SWITCHES])
    return external_data, gm_ext, figures, moon_part, figures[2], earth_tides.parameters(), flags, c_km_d()


@njit(cache=True, nogil=True)
def _frame(z):
    """A rotation matrix whose third column is the unit vector z (its x axis: e_x made normal to z)."""
    x = np.array([1.0, 0.0, 0.0]) - z[0] * z
    x = x / np.sqrt(dot3(x, x))
    y = cross3(z, x)
    m = np.empty((3, 3))
    for i in range(3):
        m[i, 0], m[i, 1], m[i, 2] = x[i], y[i], z[i]
    return m


@njit(cache=True, nogil=True)
def _point_masses(pos, vel, gm_ext, gm, r, v, planets):
    """Barycentric positions, velocities and GMs of the point masses: the Sun, the planets (if ``planets``),
    the Earth and the Moon last, these two about the EMB by their mass shares."""
    f_m = gm[1] / (gm[0] + gm[1])
    count = 2
    for j in range(pos.shape[0]):
        if j != EMB and (j == SUN or planets):
            count += 1
    x, w, mu = np.empty((count, 3)), np.empty((count, 3)), np.empty(count)
    k = 0
    for j in range(pos.shape[0]):
        if j != EMB and (j == SUN or planets):
            x[k], w[k], mu[k] = pos[j], vel[j], gm_ext[j]
            k += 1
    x[k], w[k], mu[k] = pos[EMB] - f_m * r, vel[EMB] - f_m * v, gm[0]
    x[k + 1], w[k + 1], mu[k + 1] = pos[EMB] + (1.0 - f_m) * r, vel[EMB] + (1.0 - f_m) * v, gm[1]
    return x, w, mu


@njit(cache=True, nogil=True)
def _orbit_newton(x, mu, r):
    """The relative acceleration r'' of the point masses (Newton), km/d^2: the monopole exactly, the others
    as the difference of their pulls on the Moon (last) and on the Earth (second last)."""
    n = x.shape[0]
    r2 = dot3(r, r)
    acc = -(mu[n - 2] + mu[n - 1]) / (r2 * np.sqrt(r2)) * r
    for j in range(n - 2):
        to_moon, to_earth = x[j] - x[n - 1], x[j] - x[n - 2]
        dm, de = dot3(to_moon, to_moon), dot3(to_earth, to_earth)
        acc += mu[j] * (to_moon / (dm * np.sqrt(dm)) - to_earth / (de * np.sqrt(de)))
    return acc


@njit(cache=True, nogil=True)
def _lunar_inertia(r, v, acc, rot_m, omega, moments_m, consts, gm_pair, distorted):
    """The Moon's inertia (M R^2, mantle axes) and its rate: with ``distorted``, the tide the Earth raised tau
    earlier and the spin's flattening (spinorbit.moon).  The Earth's position then, -r(t - tau), from r, v, the
    orbit's acceleration ``acc`` and the two-body jerk: 16 m from DE421's over a month (2 km to second order
    in tau with the two-body acceleration alone, which the lag angle, n tau = 0.025 rad, feels)."""
    inertia = diag3(moments_m)
    if not distorted:
        return inertia, np.zeros((3, 3))
    tau = consts[TAU_D]
    r2 = dot3(r, r)
    jerk = -gm_pair / (r2 * np.sqrt(r2)) * (v - 3.0 * dot3(r, v) / r2 * r)
    then = r - tau * v + 0.5 * tau * tau * acc - tau * tau * tau / 6.0 * jerk
    r_del, v_del = delayed_in_mantle(rot_m, omega, -then, -(v - tau * acc + 0.5 * tau * tau * jerk), tau)
    delta, inertia_rate = distortion(omega, r_del, v_del, consts)
    return inertia + delta, inertia_rate


@njit(cache=True, nogil=True)
def _sun_on_figures(sun_m, sun_e, rot_m, inertia, gm_r2_m, field_m, rot_e, inertia_e, gm_s):
    """The Sun on the Moon's degrees 2-4 and the Earth's degree 2: (the pulls on the Sun from each figure,
    ICRF; the torques on the Moon and the Earth, body axes), G-scaled; sun_m, sun_e (1, 3) km, the Sun from
    each.  Each torque is the reaction of its pull, -r x F (Euler §818)."""
    y = np.zeros(1)                               # the terms' state argument, which none of these reads
    pull_m = (point_mass.force(0.0, y, rot_m, gm_r2_m * inertia, sun_m, gm_s, ())[0]
              + gm_r2_m * harmonics.force(0.0, y, rot_m, inertia, sun_m, gm_s, field_m)[0])
    pull_e = point_mass.force(0.0, y, rot_e, inertia_e, sun_e, gm_s, ())[0]
    return (pull_m, pull_e, -mat_t_vec3(rot_m, cross3(sun_m[0], pull_m)),
            -mat_t_vec3(rot_e, cross3(sun_e[0], pull_e)))


@njit(cache=True, nogil=True)
def rhs(t, y, p):
    """dy/dt of the Earth-Moon system (state in the module docstring), t TDB days from J2000."""
    data, gm_ext, figures, moon_part, moments_e, tide_p, flags, c = p
    consts, moments_m, gm_r2_m = moon_part
    gm = figures[0]
    pos, vel = hermite_states(t, data)
    r, v, q, omega, omega_c, spin = y[0:3], y[3:6], y[6:10], y[10:13], y[13:16], y[16:19]
    x, w, mu = _point_masses(pos, vel, gm_ext, gm, r, v, flags[4] != 0.0)
    n = x.shape[0]                                  # the Earth is x[n - 2], the Moon x[n - 1]
    acc = _orbit_newton(x, mu, r)
    if flags[0] != 0.0:
        correction = eih_accelerations(x, w, mu, c, np.array([n - 2, n - 1]))[1]
        acc += correction[1] - correction[0]

    rot_m = matrix_from_quat(q)
    inertia, inertia_rate = _lunar_inertia(r, v, acc, rot_m, omega, moments_m, consts, gm[0] + gm[1],
                                           flags[2] != 0.0)
    rot_e = _frame(spin / np.sqrt(dot3(spin, spin)))
    inertia_e = diag3(moments_e)
    at_moon, sun_m, sun_e = np.empty((1, 3)), np.empty((1, 3)), np.empty((1, 3))
    at_moon[0], sun_m[0], sun_e[0] = r, pos[SUN] - x[n - 1], pos[SUN] - x[n - 2]
    force, n_m, n_e = coupled.figure_forces(rot_m, gm_r2_m * inertia, rot_e, inertia_e, at_moon, figures)
    pull_m, pull_e, sun_n_m, sun_n_e = _sun_on_figures(sun_m, sun_e, rot_m, inertia, gm_r2_m, figures[3], rot_e,
                                                       inertia_e, gm_ext[SUN:SUN + 1])
    acc += force * (gm[0] + gm[1]) / (gm[0] * gm[1]) - pull_m / gm[1] + pull_e / gm[0]

    torque_e = matvec3(rot_e, n_e + sun_n_e)
    if flags[1] != 0.0:
        r_sun, v_sun, spin_rate = sun_e[0], vel[SUN] - w[n - 2], spin / moments_e[2]
        tide = earth_tides.acceleration(r, v, r_sun, v_sun, spin_rate, tide_p)
        acc += tide
        torque_e += earth_tides.reaction(r, tide, tide_p)
    if flags[3] != 0.0:                             # geodesic precession of the heliocentric Earth (x, w)
        helio, helio_v = -sun_e[0], w[n - 2] - vel[SUN]
        torque_e += cross3(1.5 * gm_ext[SUN] / (c * c * dot3(helio, helio) ** 1.5) * cross3(helio, helio_v), spin)

    dy = np.empty(19)
    put(dy[0:3], v)
    put(dy[3:6], acc)
    put(dy[6:10], quat_rate(q, omega))
    mantle_rate, core_rate = mantle_and_core_rates(omega, omega_c, inertia, inertia_rate, (n_m + sun_n_m) / gm_r2_m,
                                                   consts)
    put(dy[10:13], mantle_rate)
    put(dy[13:16], core_rate)
    put(dy[16:19], torque_e)
    return dy


def sample_external(t_start, t_end, step_d=1.0, source="de421"):
    """The EXTERNAL bodies, barycentric, sampled every ``step_d`` days over [t_start, t_end] (TDB days):
    a HermiteOrbits whose ``data`` :func:`rhs` reads (the GMs it uses are :func:`parameters`').

    source: "de421" (the ephemeris) or "rebound" (spinorbit.orbits.nbody: an N-body run of the Sun, the
    planets, Pluto, the Earth and the Moon from DE421's state at t_start, the EMB from its Earth and Moon;
    for spans or epochs no ephemeris covers)."""
    from .orbits.interpolant import HermiteOrbits, grid
    from .orbits.kernel import open_ephemeris

    if source not in ("de421", "rebound"):
        raise InputError("source", source, "'de421' or 'rebound'")
    if source == "rebound":
        from .orbits.nbody import ReboundOrbits

        return ReboundOrbits(None, EXTERNAL, t_start, t_end, step_d, open_ephemeris("de421", t_start, t_start))
    gm = [0.0 if name == "earth_moon_barycenter" else gm_km3_d2(name) for name in EXTERNAL]
    t = grid(t_start, t_end, step_d)
    ephemeris = open_ephemeris("de421", t[0], t[-1])
    states = [ephemeris.relative_states(name, "solar_system_barycenter", t) for name in EXTERNAL]
    return HermiteOrbits(EXTERNAL, gm, t[0], step_d, np.array([s[0] for s in states]),
                         np.array([s[1] for s in states]), source="de421")


def earth_axis(states):
    """The Earth's spin axis (unit, ICRF) of states (n, 19)."""
    spin = np.atleast_2d(states)[:, 16:19]
    return spin / np.linalg.norm(spin, axis=1)[:, None]
