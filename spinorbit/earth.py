"""The rigid Earth under the Moon's and Sun's torques: precession and nutation (Euler ch. 16).

Layer 2 (numpy, numba).  An oblate (optionally triaxial) rigid Earth with the
IAU 2006 dynamical ellipticity H_d = (C - A)/C, driven by point masses through
the ch. 16 P91 gravity-gradient torque (§815).  Moments are in units of C.
Two integrations of the same physics, both as SpinSystems for a fixed-step
integrator (rk8):

* **full** -- Euler's equations (§813) with the daily spin resolved:
  ``y = [q (body -> GCRS), omega (body axes, rad/d)]``;
* **gyroscopic** -- only the angular momentum moves, dL/dt = N (the torque
  evaluated for the figure axis recovered from L to second order in 1/Omega,
  exact otherwise for an axisymmetric body):
  ``y = [q_L, 0, 0, |L|/C]`` with q_L a twist-free frame whose z axis is L/|L|.

Frames: positions and outputs in GCRS (geocentric ICRF axes).  Euler's
equations hold in the dynamically non-rotating frame, which turns with respect
to GCRS at the geodesic precession ``Omega_gp`` (prograde about the ecliptic
pole, de Sitter), so the kinematics add ``Omega_gp`` to the body rate and the
observed precession in longitude is 1.919883"/cy less than the dynamical one.

Parameters of both right-hand sides: ``p = (moments, gm (n,), data, term_params, extra)``
(``earth_params``) with ``extra = [Omega_gp (3, rad/d, GCRS), k_J2 (1/d)]``; the figure's
anisotropy, and so the torque, is scaled by (1 + k_J2 t), t in TDB days from J2000 (secular
change of J2).  The full model takes any terms (spinorbit.terms, default the point masses);
the gyroscopic one is built on the point masses' tidal tensor alone.
"""
import functools
import math

import numpy as np
from numba import njit

from .constants import ARCSEC, JULIAN_CENTURY_D
from .bodies.earth import (A_AXIS_LONGITUDE_DEG, B_MINUS_A_OVER_C, C_MR2,  # noqa: F401 (the model's)
                           EQUATORIAL_RADIUS_KM, ERA_RATE_RAD_D, GEODESIC_PRECESSION_ARCSEC_CY, H_D, J2, J2_RATE_PER_CY,
                           J4)
from .dynamics import SpinSystem, euler_omega_dot
from .errors import PhysicsError
from .linker import free, link, template
from .rotations import (cross3, diag3, dot3, mat_t_vec3, matrix_from_quat, matvec3, put, quat_from_matrix,
                        quat_rate)
from .terms import point_mass
from .terms.base import fuse

positions, terms, torque, tensor = free("positions", "terms", "torque", "tensor")    # bound by link()

POINT_MASSES = (point_mass.build(None),)
# The Earth's heliocentric orbit: eccentricity and the Sun's mean anomaly l' = l'_0 + n' t (rad, rad/d),
# Simon et al. 1994 as in the IERS Conventions 2010 (eq. 5.43, linear part).
EARTH_ORBIT_ECCENTRICITY = 0.0167086
SUN_MEAN_ANOMALY_RAD = (math.radians(357.52910918), math.radians(129596581.0481 / 3600.0) / JULIAN_CENTURY_D)


def earth_moments(h_d=H_D, b_minus_a_over_c=0.0):
    """(A, B, C)/C with (C - (A + B)/2)/C = h_d and (B - A)/C as given."""
    return np.array([1.0 - h_d - b_minus_a_over_c / 2, 1.0 - h_d + b_minus_a_over_c / 2, 1.0])


def earth_params(moments, gm, data, extra, term_params=((),)):
    """Parameter tuple of both models: (moments, gm (n,), data, term_params, extra); ``term_params``
    those of the fused terms (default: the point masses')."""
    return (np.asarray(moments, dtype=float), np.asarray(gm, dtype=float), data, term_params,
            np.asarray(extra, dtype=float))


def extra_parameters(ecliptic_pole, geodesic=True, j2_rate=True, j4=False, geodesic_nutation=False):
    """``extra`` = [Omega_gp (3), k_J2, J4 R^2/(C/MR^2), 3 e, l'_0, n']: geodesic precession about
    ``ecliptic_pole`` (GCRS unit vector), the secular J2 rate, the J4 coefficient (km^2, 0 = off), and the
    annual modulation of the geodesic precession (0 = off; both for the gyroscopic model)."""
    rate = GEODESIC_PRECESSION_ARCSEC_CY * ARCSEC / JULIAN_CENTURY_D if geodesic else 0.0
    k = J2_RATE_PER_CY / J2 / JULIAN_CENTURY_D if j2_rate else 0.0
    j4_coef = J4 * EQUATORIAL_RADIUS_KM**2 / C_MR2 if j4 else 0.0
    modulation = 3.0 * EARTH_ORBIT_ECCENTRICITY if geodesic and geodesic_nutation else 0.0
    pole = np.asarray(ecliptic_pole, dtype=float)
    return np.array([*(rate * pole / np.linalg.norm(pole)), k, j4_coef, modulation, *SUN_MEAN_ANOMALY_RAD])



@njit(cache=True)
def geodesic_rate(extra, t):
    """The dynamical frame's rate against the GCRS (rad/d, GCRS) at TDB day t: de Sitter's precession, whose
    size goes as h/r^3 over the Earth's orbit, (1 + e cos f)^3 ~ 1 + 3 e cos l' to first order in e; the
    annual term integrates to the geodesic nutation, 3 e Omega_gp / n' = 0.153 mas in psi (Fukushima 1991)."""
    return extra[:3] * (1.0 + extra[5] * math.cos(extra[6] + extra[7] * t))


# --- full model: Euler's equations with the daily spin ------------------------

@template("positions", "terms")
def full_torque(t, y, p):
    """Body-frame torque of the fused terms on the figure I (1 + k_J2 t), I = diag(p[0])."""
    inertia = diag3(p[0]) * (1.0 + p[4][3] * t)
    return terms(t, y, matrix_from_quat(y[:4]), inertia, positions(t, p[2]), p[1], p[3])


def make_full_torque(positions, terms=None):
    """torque(t, y, p) of the fused ``terms`` (default: the point masses, §815) on the figure I (1 + k_J2 t).

    ``positions(t, data) -> (n, 3)`` km, GCRS, relative to the geocentre.
    """
    return link(full_torque, positions=positions, terms=fuse(POINT_MASSES)[0] if terms is None else terms)


@template("torque")
def full_rhs(t, y, p):
    """Euler's equations (§813) + kinematics in the frame turning at Omega_gp = p[4][:3] w.r.t. GCRS."""
    extra = p[4]
    frame_rate_body = mat_t_vec3(matrix_from_quat(y[:4]), extra[:3])
    dy = np.zeros_like(y)
    put(dy[:4], quat_rate(y[:4], y[4:7] + frame_rate_body))
    put(dy[4:7], euler_omega_dot(p[0], y[4:7], torque(t, y, p)))
    return dy


def make_full_rhs(positions, terms=None):
    """rhs(t, y, p) of Euler's equations (§813) + kinematics with geodesic precession."""
    return link(full_rhs, torque=make_full_torque(positions, terms))


# --- gyroscopic model: the angular momentum direction -------------------------

@template("positions")
def tidal_tensor(t, p):
    """3 (1 + k_J2 t) sum GM r r^T / r^5 (GCRS, 1/d^2) of the point masses at ``positions``."""
    gm, data, extra = p[1], p[2], p[4]
    r = positions(t, data)
    out = np.zeros((3, 3))
    for i in range(gm.shape[0]):
        s2 = r[i, 0] ** 2 + r[i, 1] ** 2 + r[i, 2] ** 2
        k = 3.0 * gm[i] / (s2 * s2 * math.sqrt(s2))
        for a in range(3):
            for b in range(3):
                out[a, b] += k * r[i, a] * r[i, b]
    return out * (1.0 + extra[3] * t)


def make_tidal_tensor(positions):
    """tidal_tensor(t, p) = 3 (1 + k_J2 t) sum GM r r^T / r^5 (GCRS, 1/d^2).

    For an axisymmetric body with figure axis z the torque of all the point
    masses is then N = (C - A) (T z) x z (§815 summed over the masses).
    """
    return link(tidal_tensor, positions=positions)


@njit(cache=True)
def _axis_torque(tensor, z, c_minus_a):
    """(C - A) (T z) x z: inertial torque on an axisymmetric body with figure axis z."""
    return c_minus_a * cross3(matvec3(tensor, z), z)


@njit(cache=True)
def _slow_figure_axis(t0, t_dot, ell, lc, moments):
    """Figure axis on the forced solution, from the tidal tensor and its rate.

    For an axisymmetric body dz/dt = (L x z)/A exactly; on the slow (forced)
    solution z = ell - (ell x ell')/lam - ell''_perp/lam^2 + O(lam^-3), lam = |L|/A,
    ell' = N_perp/|L|, ell''_perp = N'_perp/|L| (the Oppolzer terms).  N(ell) is
    perpendicular to ell, so ell x ell' = ell x N/|L| and ell''_perp = N'/|L|.
    """
    a = 0.5 * (moments[0] + moments[1])
    lam = lc * moments[2] / a
    c_minus_a = moments[2] - a
    n0 = _axis_torque(t0, ell, c_minus_a / (lc * lam))
    n_dot = _axis_torque(t_dot, ell, c_minus_a / (lc * lam * lam))
    z = ell - cross3(ell, n0) - n_dot
    return z / math.sqrt(dot3(z, z))


_H_DIFF = 1.0 / 64.0      # d, central difference for the tensor rate


@template("tensor")
def figure_axis(t, ell, lc, p):
    """Figure axis (GCRS) on the forced solution from the unit L direction ``ell``, |L|/C = ``lc``."""
    t_dot = (tensor(t + _H_DIFF, p) - tensor(t - _H_DIFF, p)) / (2.0 * _H_DIFF)
    return _slow_figure_axis(tensor(t, p), t_dot, ell, lc, p[0])


def make_figure_axis(positions):
    """figure_axis(t, ell, lc, p): figure axis (GCRS) from the unit L direction ``ell``, |L|/C = ``lc``."""
    return link(figure_axis, tensor=make_tidal_tensor(positions))


@njit(cache=True)
def j4_torque(r_all, gm, z, j4_coef):
    """Inertial torque per C of the point masses on the Earth's J4 (axisymmetric about the unit axis z).

    From U_4 = GM_E J4 R^4 P4(s)/r^5 (s = z.r/r): N = G m M_E J4 R^4 P4'(s) (r x z)/r^6, per
    C = (C/MR^2) M_E R^2: GM_m [J4 R^2/(C/MR^2)] P4'(s) (r x z)/r^6, P4'(s) = (35 s^3 - 15 s)/2.
    (The same steps for J2 give (C - A)/C (T z) x z, the tidal-tensor torque.)
    """
    total = np.zeros(3)
    for i in range(gm.shape[0]):
        r = r_all[i]
        r2 = dot3(r, r)
        rn = math.sqrt(r2)
        s = dot3(r, z) / rn
        total += gm[i] * j4_coef * 0.5 * (35.0 * s**3 - 15.0 * s) / (r2 * r2 * r2) * cross3(r, z)
    return total


@template("tensor", "positions")
def gyroscopic_rhs(t, y, p):
    """dL/dt = N(z(L)) + Omega_gp x L for y = [q_L, 0, 0, |L|/C]."""
    moments, extra = p[0], p[4]
    ell = _third_axis(y)
    lc = y[6]
    t0 = tensor(t, p)
    t_dot = (tensor(t + _H_DIFF, p) - tensor(t - _H_DIFF, p)) / (2.0 * _H_DIFF)
    z = _slow_figure_axis(t0, t_dot, ell, lc, moments)
    torque = _axis_torque(t0, z, moments[2] - 0.5 * (moments[0] + moments[1]))
    if extra[4] != 0.0:
        torque += j4_torque(positions(t, p[2]), p[1], z, extra[4])
    ell_dot = (torque - dot3(torque, ell) * ell) / lc + cross3(geodesic_rate(extra, t), ell)
    w = cross3(ell, ell_dot)          # inertial rate of the twist-free L frame
    dy = np.zeros_like(y)
    dy[0] = -0.5 * (w[0] * y[1] + w[1] * y[2] + w[2] * y[3])      # dq/dt = (0, w) q / 2
    dy[1] = 0.5 * (w[0] * y[0] + w[1] * y[3] - w[2] * y[2])
    dy[2] = 0.5 * (w[1] * y[0] + w[2] * y[1] - w[0] * y[3])
    dy[3] = 0.5 * (w[2] * y[0] + w[0] * y[2] - w[1] * y[1])
    return dy


def make_gyroscopic_rhs(positions):
    """rhs(t, y, p) of dL/dt = N(z(L)) + Omega_gp x L for y = [q_L, 0, 0, |L|/C]."""
    return link(gyroscopic_rhs, tensor=make_tidal_tensor(positions), positions=positions)


@njit(cache=True)
def _third_axis(q):
    """Third column of the rotation matrix of a unit quaternion (the frame's z axis)."""
    w, x, y, z = q[0], q[1], q[2], q[3]
    return np.array([2.0 * (x * z + w * y), 2.0 * (y * z - w * x), 1.0 - 2.0 * (x * x + y * y)])


def figure_axes_from_gyroscopic(positions, t, y, params):
    """Figure axes (len(t), 3) GCRS from gyroscopic states y (len(t), 7)."""
    figure_axis = make_figure_axis(positions)
    return np.array([figure_axis(ti, _third_axis(yi), yi[6], params)
                     for ti, yi in zip(t, y)])


# --- forced initial conditions ---------------------------------------------------

def forced_angular_momentum(positions, t0, z0, spin_rate, params, iterations=4):
    """Unit L direction and |L|/C whose forced figure axis is ``z0`` and whose omega.z = ``spin_rate``.

    Solves z(ell) = z0 by fixed-point iteration (the Oppolzer offset L - z is ~10 mas).
    """
    figure_axis = make_figure_axis(positions)
    z0 = np.asarray(z0, dtype=float) / np.linalg.norm(z0)
    ell, lc = z0.copy(), spin_rate
    for _ in range(iterations):
        ell = ell + (z0 - figure_axis(t0, ell, lc, params))
        ell /= np.linalg.norm(ell)
        lc = spin_rate / float(ell @ z0)          # omega_z = L.z / C
    return ell, lc


def _frame(z, x_hint):
    """Right-handed orthonormal columns (x, y, z) with z given and x nearest ``x_hint``."""
    z = z / np.linalg.norm(z)
    x = x_hint - (x_hint @ z) * z
    x /= np.linalg.norm(x)
    return np.column_stack([x, np.cross(z, x), z])


def full_system(positions, params, t0, z0, x0, spin_rate=ERA_RATE_RAD_D, forced=True, terms=None):
    """SpinSystem of the full model started on figure axis ``z0`` (GCRS) with body x axis near ``x0``.

    ``terms``: the fused torque of the terms (terms.base.fuse; its parameters in params[3]),
    default the point masses.  The forced start is computed for the point masses alone.

    forced=True: omega_perp from the forced L (Oppolzer terms), so no free
    nutation starts; forced=False: omega along the figure axis (starts one).
    """
    moments = params[0]
    rot = _frame(np.asarray(z0, float), np.asarray(x0, float))
    if forced:
        ell, lc = forced_angular_momentum(positions, t0, z0, spin_rate, params)
        omega = (rot.T @ (lc * moments[2] * ell)) / moments
    else:
        omega = np.array([0.0, 0.0, spin_rate])
    y0 = np.concatenate([quat_from_matrix(rot), omega])
    # a rigid body under an external torque, its Euler equations in the frame turning at
    # Omega_gp w.r.t. GCRS: splitting methods take the torque and that frame rate
    return SpinSystem(make_full_rhs(positions, terms), params, t0, y0, moments, make_full_torque(positions, terms),
                      "earth (full)", {"frame_rate": params[4][:3].copy()})


def gyroscopic_system(positions, params, t0, z0, spin_rate=ERA_RATE_RAD_D):
    """SpinSystem of the gyroscopic model whose forced figure axis at ``t0`` is ``z0`` (GCRS)."""
    moments = params[0]
    if abs(moments[1] - moments[0]) > 1e-12 * moments[2]:
        raise PhysicsError(f"the gyroscopic model needs an axisymmetric Earth (A = B), got moments "
                           f"{moments.tolist()}; use the full model for a triaxial Earth")
    ell, lc = forced_angular_momentum(positions, t0, z0, spin_rate, params)
    rot = _frame(ell, np.array([1.0, 0.0, 0.0]) if abs(ell[0]) < 0.9 else np.array([0.0, 1.0, 0.0]))
    y0 = np.concatenate([quat_from_matrix(rot), [0.0, 0.0, lc]])
    return SpinSystem(make_gyroscopic_rhs(positions), params, t0, y0, moments, None, "earth (gyroscopic)",
                      {"figure_axes": functools.partial(figure_axes_from_gyroscopic, positions)})


def figure_axes_from_full(y):
    """Body z axes in GCRS (len, 3) from full-model states."""
    return np.array([matrix_from_quat(yi[:4])[:, 2] for yi in y])


def free_nutation_amplitude(t, omega_body, moments):
    """Amplitude (rad) of the free (Euler) nutation, the angle between figure axis and L it adds.

    Least-squares fit of m = (w_x + i w_y)/w_z to a + b exp(i sigma_E t) with the
    Euler (Chandler, rigid) frequency sigma_E = w_z (C - A)/A in body axes
    (ch. 15; ~305 d for the Earth).  tan(angle) = (A/C)|m| for an axisymmetric top.
    Sample densely enough to resolve the forced nearly-diurnal terms (<= 0.25 d).
    """
    a, c = 0.5 * (moments[0] + moments[1]), moments[2]
    w_z = float(np.mean(omega_body[:, 2]))
    m = (omega_body[:, 0] + 1j * omega_body[:, 1]) / omega_body[:, 2]
    sigma = w_z * (c - a) / a
    design = np.column_stack([np.ones_like(t), np.exp(1j * sigma * (t - t[0]))])
    coef = np.linalg.lstsq(design, m, rcond=None)[0]
    return float(a / c * abs(coef[1]))
