"""The closed Earth-Moon system: the relative orbit and both rotations in one state, coupled both ways.

State (20,): ``y = [r (3), v (3), q_m (4), w_m (3), q_e (4), w_e (3)]`` with r the Moon from the Earth
(km, ICRF), v = dr/dt (km/d), q body -> ICRF and w body axes (rad/d) for the Moon (m) and the Earth (e).
Every mass is multiplied by G (GM, km^3/d^2) and every inertia too (G I, km^5/d^2), so that torques,
forces and energies are G times the physical ones and km, d stay the only units.

Interactions, each with its reaction (Euler §818; Folkner et al. 2014, IPN PR 42-196):
the monopole; the Moon's degree-2 figure (terms.point_mass) and degree 3-4 field (terms.harmonics) with
the Earth as a point mass; the Earth's degree-2 figure and J3, J4 with the Moon as a point mass; the
Earth's J2 with the Moon's degree 2 (terms.figure_figure, the pole the Earth's body z axis).  The Moon:
rigid, DE421's moments and field (bodies.moon); the Earth: rigid, axisymmetric, C = C/(M a^2) M a^2,
A = B = C (1 - H_d) (bodies.earth), J3 from the DE421 header (J3E) and J4 from EGM2008 (bodies.earth.J4,
-1.62e-6), both at the header's RE (= EGM2008's a): the header's J4E is +1.619974e-6, the opposite of
the Earth's known sign.  No Sun, no tides.

The relative acceleration is F_moon / m_m - F_earth / m_e = F_moon / mu (mu = m_e m_m / (m_e + m_m)),
and the total angular momentum mu r x v + R_m I_m w_m + R_e I_e w_e and the energy
mu v^2 / 2 - G m_e m_m / r + the figures' interaction energies + both spins' kinetic energies are
conserved (:func:`invariants`).
"""
import numpy as np
from numba import njit

from .bodies import earth
from .bodies.de421_header import gm_km3_d2, header
from .bodies.moon import de421
from .dynamics import euler_omega_dot
from .errors import InputError
from .rotations import cross3, diag3, dot3, mat_t_vec3, matrix_from_quat, matvec3, put, quat_from_matrix, quat_rate
from .terms import figure_figure, harmonics, point_mass

# Which interactions are on: the ``on`` flags of the parameters, in this order.
FIGURES = ("moon_figure", "moon_harmonics", "earth_figure", "earth_harmonics", "figure_figure")


def parameters(figures=FIGURES):
    """p = (gm (2,) [earth, moon], moments_m (3,), moments_e (3,), moon field, earth field, on (5,)):
    G-scaled principal moments (km^5/d^2), fields as terms.harmonics' parameters (degrees 3-4)."""
    unknown = sorted(set(figures) - set(FIGURES))
    if unknown:
        raise InputError("figures", unknown, f"names from {list(FIGURES)}")
    moon, h = de421(), header()
    gm = np.array([gm_km3_d2("earth"), gm_km3_d2("moon")])
    moments_m = moon.moments * gm[1] * moon.radius_km ** 2
    c_e = earth.C_MR2 * gm[0] * earth.EQUATORIAL_RADIUS_KM ** 2
    moments_e = np.array([c_e * (1 - earth.H_D), c_e * (1 - earth.H_D), c_e])
    c_nm_e = np.zeros((5, 5))
    c_nm_e[3, 0], c_nm_e[4, 0] = -h["J3E"], -earth.J4
    moon_field = (float(moon.radius_km), np.ascontiguousarray(moon.c_nm), np.ascontiguousarray(moon.s_nm), 3, 4)
    earth_field = (float(h["RE"]), c_nm_e, np.zeros((5, 5)), 3, 4)
    on = np.array([1.0 if name in figures else 0.0 for name in FIGURES])
    return gm, moments_m, moments_e, moon_field, earth_field, on


@njit(cache=True, nogil=True)
def _geometry(y, p):
    """Both attitudes (body -> ICRF), both inertia tensors (body axes), the Moon from the Earth and the Earth
    from the Moon as (1, 3) rows: what every interaction is evaluated with."""
    at_moon, at_earth = np.empty((1, 3)), np.empty((1, 3))
    for k in range(3):
        at_moon[0, k], at_earth[0, k] = y[k], -y[k]
    return (matrix_from_quat(y[6:10]), matrix_from_quat(y[13:17]), diag3(p[1]), diag3(p[2]), at_moon, at_earth)


@njit(cache=True, nogil=True)
def interactions(y, p):
    """The figures' part: (force on the Moon, ICRF; torque on the Moon, its body axes; torque on the Earth,
    its body axes), G-scaled.  The force on the Earth is minus the force on the Moon."""
    rot_m, rot_e, inertia_m, inertia_e, at_moon, at_earth = _geometry(y, p)
    return figure_forces(rot_m, inertia_m, rot_e, inertia_e, at_moon, p)


@njit(cache=True, nogil=True)
def figure_forces(rot_m, inertia_m, rot_e, inertia_e, at_moon, p):
    """:func:`interactions` for given attitudes (body -> ICRF), G-scaled inertia tensors (body axes) and the
    Moon seen from the Earth ((1, 3), km, ICRF); the Earth's degree 2 is its inertia's, the rest is p's."""
    gm, moments_m, moments_e, moon_field, earth_field, on = p
    at_earth = -at_moon
    y = np.zeros(1)                               # the terms' state argument, which none of these reads
    gm_e, gm_m = gm[0:1], gm[1:2]
    force, n_m, n_e = np.zeros(3), np.zeros(3), np.zeros(3)
    # each figure's torque is the reaction of its pull on the other body about its centre: N = -r x F (§818)
    if on[0] != 0.0:        # the Moon's degree 2 and the Earth as a point mass
        pull = point_mass.force(0.0, y, rot_m, inertia_m, at_earth, gm_e, ())[0]
        force -= pull
        n_m -= mat_t_vec3(rot_m, cross3(at_earth[0], pull))
    if on[1] != 0.0:        # the Moon's degrees 3-4 (per M R^2) and the Earth
        pull = gm[1] * moon_field[0] ** 2 * harmonics.force(0.0, y, rot_m, inertia_m, at_earth, gm_e, moon_field)[0]
        force -= pull
        n_m -= mat_t_vec3(rot_m, cross3(at_earth[0], pull))
    if on[2] != 0.0:        # the Earth's degree 2 and the Moon as a point mass
        pull = point_mass.force(0.0, y, rot_e, inertia_e, at_moon, gm_m, ())[0]
        force += pull
        n_e -= mat_t_vec3(rot_e, cross3(at_moon[0], pull))
    if on[3] != 0.0:        # the Earth's J3, J4 and the Moon
        pull = gm[0] * earth_field[0] ** 2 * harmonics.force(0.0, y, rot_e, inertia_e, at_moon, gm_m, earth_field)[0]
        force += pull
        n_e -= mat_t_vec3(rot_e, cross3(at_moon[0], pull))
    if on[4] != 0.0:        # the Earth's J2 (G (C - A)) with the Moon's degree 2
        pole = np.array([rot_e[0, 2], rot_e[1, 2], rot_e[2, 2]])
        torque, pull, reaction = figure_figure.with_pole(rot_m, inertia_m, at_earth[0], pole,
                                                         inertia_e[2, 2] - inertia_e[0, 0])
        n_m += torque
        force -= pull
        n_e += mat_t_vec3(rot_e, reaction)
    return force, n_m, n_e


@njit(cache=True, nogil=True)
def rhs(t, y, p):
    """dy/dt of the closed Earth-Moon system (state in the module docstring)."""
    gm, moments_m, moments_e = p[0], p[1], p[2]
    force, n_m, n_e = interactions(y, p)
    r = y[0:3]
    r2 = dot3(r, r)
    mu = gm[0] * gm[1] / (gm[0] + gm[1])
    dy = np.zeros(20)
    put(dy[0:3], y[3:6])
    put(dy[3:6], -(gm[0] + gm[1]) / (r2 * np.sqrt(r2)) * r + force / mu)
    put(dy[6:10], quat_rate(y[6:10], y[10:13]))
    put(dy[10:13], euler_omega_dot(moments_m, y[10:13], n_m))
    put(dy[13:17], quat_rate(y[13:17], y[17:20]))
    put(dy[17:20], euler_omega_dot(moments_e, y[17:20], n_e))
    return dy


@njit(cache=True, nogil=True)
def energy(y, p):
    """Total energy, G-scaled (km^5/d^4): orbit, both spins and the figures' interaction energies."""
    gm, moments_m, moments_e, moon_field, earth_field, on = p
    rot_m, rot_e, inertia_m, inertia_e, at_moon, at_earth = _geometry(y, p)
    gm_e, gm_m = gm[0:1], gm[1:2]
    mu = gm[0] * gm[1] / (gm[0] + gm[1])
    total = 0.5 * mu * dot3(y[3:6], y[3:6]) - gm[0] * gm[1] / np.sqrt(dot3(y[0:3], y[0:3]))
    for k in range(3):
        total += 0.5 * (moments_m[k] * y[10 + k] ** 2 + moments_e[k] * y[17 + k] ** 2)
    if on[0] != 0.0:
        total += point_mass.energy(0.0, y, rot_m, inertia_m, at_earth, gm_e, ())
    if on[1] != 0.0:
        total += gm[1] * moon_field[0] ** 2 * harmonics.energy(0.0, y, rot_m, inertia_m, at_earth, gm_e, moon_field)
    if on[2] != 0.0:
        total += point_mass.energy(0.0, y, rot_e, inertia_e, at_moon, gm_m, ())
    if on[3] != 0.0:
        total += gm[0] * earth_field[0] ** 2 * harmonics.energy(0.0, y, rot_e, inertia_e, at_moon, gm_m, earth_field)
    if on[4] != 0.0:
        pole = np.array([rot_e[0, 2], rot_e[1, 2], rot_e[2, 2]])
        total += figure_figure.energy(inertia_m, mat_t_vec3(rot_m, at_earth[0]), mat_t_vec3(rot_m, pole),
                                      moments_e[2] - moments_e[0])
    return total


@njit(cache=True, nogil=True)
def angular_momentum(y, p):
    """Total angular momentum about the barycentre, ICRF, G-scaled: mu r x v + R_m I_m w_m + R_e I_e w_e."""
    gm, moments_m, moments_e = p[0], p[1], p[2]
    mu = gm[0] * gm[1] / (gm[0] + gm[1])
    spin_m = matvec3(matrix_from_quat(y[6:10]), moments_m * y[10:13])
    spin_e = matvec3(matrix_from_quat(y[13:17]), moments_e * y[17:20])
    return mu * cross3(y[0:3], y[3:6]) + spin_m + spin_e


def invariants(states, p):
    """(energy (n,), angular momentum (n, 3)) of states (n, 20), G-scaled."""
    states = np.atleast_2d(states)
    return (np.array([energy(y, p) for y in states]), np.array([angular_momentum(y, p) for y in states]))


def drifts(states, p):
    """Largest relative changes from the first state: |L|, the L vector (over |L|), the energy (over |E|)."""
    e, big_l = invariants(states, p)
    norm = np.linalg.norm(big_l, axis=1)
    return {"L_norm_rel_drift": float(np.max(np.abs(norm / norm[0] - 1))),
            "L_vector_rel_drift": float(np.max(np.linalg.norm(big_l - big_l[0], axis=1)) / norm[0]),
            "energy_rel_drift": float(np.max(np.abs(e / e[0] - 1)))}


def attitude_with_pole(pole, spin_rad_d):
    """(q, w) of a body whose z axis is ``pole`` (ICRF) spinning about it at ``spin_rad_d`` (rad/d)."""
    z = np.asarray(pole, dtype=float) / np.linalg.norm(pole)
    x = np.cross([0.0, 0.0, 1.0], z) if abs(z[2]) < 0.9 else np.cross([1.0, 0.0, 0.0], z)
    x /= np.linalg.norm(x)
    return quat_from_matrix(np.column_stack([x, np.cross(z, x), z])), np.array([0.0, 0.0, spin_rad_d])


def state(r, v, q_m, w_m, q_e, w_e):
    """The state vector (20,) from its parts."""
    return np.concatenate([r, v, q_m, w_m, q_e, w_e]).astype(float)
