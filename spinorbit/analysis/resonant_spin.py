"""A body in the 3:2 spin-orbit resonance on an N-body orbit (Mercury): its mean orbit, its start in the Cassini
state on the forced libration, and its libration in longitude and obliquity measured from a run.

The mean orbit is fitted to the osculating elements of the orbit source's samples over the run (the Sun seen
from the body, reversed): a linear mean anomaly (mean motion n), the mean eccentricity, the orbit normal and
the perihelion direction with their rates (spinorbit.analysis.cassini).  The start (``resonant_start``): the
spin axis in Peale's Cassini state for the normal's fitted speed; the long axis at (3/2) M + g(M) from the
perihelion in the orbit plane, turning at (3/2) n + g'(M), with g the linear forced libration of the librating
moment (the mantle's, C_m) (spinorbit.analysis.planar_spin_orbit.libration_theory); the core turning at
(3/2) n about the same axis.  What the start leaves free (the free libration, ~12 yr; the free precession about
the Cassini state, ~1300 yr) is measured, not assumed away: the libration fit carries the free libration, and
``cassini.settled_axis`` finds the state the spin circles.
"""
from dataclasses import dataclass

import numpy as np

from ..base.rotations import matrices_from_quats, quat_from_matrix
from .cassini import linear_fit, mean_normal, osculating
from .planar_spin_orbit import libration_theory
from .spans import resolvable

HARMONICS = 4           # harmonics of the mean anomaly fitted to the libration


@dataclass(frozen=True)
class MeanOrbit:
    """The orbit's mean elements at ``t_ref`` (TDB d): mean motion n (rad/d), mean anomaly, eccentricity, the unit
    orbit normal and its rate (rad/d, perpendicular to it), the unit perihelion direction (in the orbit plane)."""

    t_ref: float
    n: float
    mean_anomaly: float
    e: float
    normal: np.ndarray
    normal_rate: np.ndarray
    perihelion: np.ndarray

    def anomaly(self, t):
        """The mean anomaly (rad) at TDB days t."""
        return self.mean_anomaly + self.n * (np.asarray(t) - self.t_ref)


def samples(orbits, t_start, t_end, body=0):
    """(t, r, v): the body's orbit about the attracting mass ``body`` of ``orbits`` (a HermiteOrbits of that mass
    seen from the spinning body), at its samples in [t_start, t_end]."""
    t0, step = orbits.data[0]
    t = t0 + step * np.arange(orbits.data[1].shape[1])
    inside = (t >= min(t_start, t_end)) & (t <= max(t_start, t_end))
    return t[inside], -orbits.data[1][body][inside], -orbits.data[2][body][inside]


def mean_orbit(orbits, t_start, t_end, gm, t_ref=None):
    """The MeanOrbit fitted over [t_start, t_end] (GM of the pair, km^3/d^2), at ``t_ref`` (default t_start)."""
    t_ref = t_start if t_ref is None else t_ref
    t, r, v = samples(orbits, t_start, t_end)
    elements = osculating(r, v, gm)
    anomaly, n = linear_fit(t, elements["mean_anomaly"], t_ref)
    normal, normal_rate = mean_normal(t, elements["normal"], t_ref)
    perihelion = linear_fit(t, elements["perihelion"], t_ref)[0]
    perihelion -= normal * (normal @ perihelion)
    return MeanOrbit(t_ref, float(n), float(anomaly), float(elements["e"].mean()), normal, normal_rate,
                     perihelion / np.linalg.norm(perihelion))


def resonant_start(orbit, axis, gamma_mantle):
    """{q0, omega0, omega_core0, theory}: the body at orbit.t_ref with its spin along ``axis`` in the 3:2 state
    on the linear forced libration of (B - A)/C_m = ``gamma_mantle`` (module docstring)."""
    theory = libration_theory(gamma_mantle, orbit.e)
    k = np.arange(1, theory["g"].size + 1)
    m0 = orbit.mean_anomaly
    theta = 1.5 * m0 + float(np.sum(theory["g"] * np.sin(k * m0)))
    rate = 1.5 * orbit.n + orbit.n * float(np.sum(k * theory["g"] * np.cos(k * m0)))
    along = np.cos(theta) * orbit.perihelion + np.sin(theta) * np.cross(orbit.normal, orbit.perihelion)
    x = along - axis * (axis @ along)
    x /= np.linalg.norm(x)
    matrix = np.column_stack([x, np.cross(axis, x), axis])
    return {"q0": quat_from_matrix(matrix), "omega0": np.array([0.0, 0.0, rate]),
            "omega_core0": np.array([0.0, 0.0, 1.5 * orbit.n]), "theory": theory}


def body_axes(q):
    """(long axes, spin axes) (n, 3) in inertial axes of attitudes q (n, 4)."""
    m = matrices_from_quats(q)
    return m[:, :, 0], m[:, :, 2]


def libration(t, q, orbit):
    """gamma = theta - (3/2) M (rad, unwrapped): theta the long axis's angle from the perihelion at t_ref about the
    orbit normal there, M the mean anomaly."""
    long_axis = body_axes(q)[0]
    y = np.cross(orbit.normal, orbit.perihelion)
    theta = np.unwrap(np.arctan2(long_axis @ y, long_axis @ orbit.perihelion))
    gamma = theta - 1.5 * orbit.anomaly(t)
    return gamma - 2 * np.pi * np.round(gamma[0] / (2 * np.pi))


def fit_libration(t, gamma, orbit, w0):
    """{amplitude_88d (signed by its sin M part), cos_88d, amplitudes of M's harmonics, free (at w0, or None when
    the span cannot resolve it), residual_rms} (rad) of a fit of [1, t, t^2, sin kM, cos kM (k <= HARMONICS),
    sin w0 t, cos w0 t] to gamma."""
    dt = t - orbit.t_ref
    m = orbit.anomaly(t)
    keep_free = bool(resolvable(np.array([w0]), abs(dt[-1] - dt[0]))[0])
    columns = [np.ones_like(dt), dt, dt * dt]
    for k in range(1, HARMONICS + 1):
        columns += [np.sin(k * m), np.cos(k * m)]
    if keep_free:
        columns += [np.sin(w0 * dt), np.cos(w0 * dt)]
    design = np.column_stack(columns)
    coef = np.linalg.lstsq(design, gamma, rcond=None)[0]
    pairs = coef[3:3 + 2 * HARMONICS].reshape(-1, 2)
    return {"amplitude_88d": float(np.copysign(np.hypot(*pairs[0]), pairs[0][0])), "cos_88d": float(pairs[0][1]),
            "harmonics": np.hypot(pairs[:, 0], pairs[:, 1]),
            "free": float(np.hypot(*coef[-2:])) if keep_free else None,
            "residual_rms": float(np.std(gamma - design @ coef))}


@dataclass(frozen=True)
class Interior:
    """A body's degree-2 figure (J2, C22 unnormalised) and interior: C/(M R^2), the librating mantle's share C_m/C,
    and the time (d) in which friction at the core-mantle boundary pulls the fluid core to the mantle's rotation
    (k_v = C_c / coupling_time_d)."""

    j2: float
    c22: float
    c_mr2: float
    cm_over_c: float
    coupling_time_d: float

    def moments(self):
        """(A, B, C) in units of M R^2."""
        return np.array([self.c_mr2 - self.j2 - 2 * self.c22, self.c_mr2 - self.j2 + 2 * self.c22, self.c_mr2])

    def gamma_mantle(self):
        """(B - A)/C_m: what sets the mantle's forced libration."""
        return 4 * self.c22 / (self.c_mr2 * self.cm_over_c)


def cassini_system(orbits, interior, t_start, t_end, gm, inclination, obliquity_offset=0.0):
    """(System, context) of the body of ``interior`` under ``orbits``' point masses (the Sun first), a mantle over a
    fluid core (spinorbit.models.rotators.MantleCore), started at t_start in the Cassini state of Peale's equation
    for the orbit normal's speed fitted over [t_start, t_end] (plus ``obliquity_offset`` rad, away from the
    orbit normal), on the forced libration.  context: {orbit (MeanOrbit), alpha (rad/d), peale_obliquity (rad),
    axis, theory, inclination (rad)}."""
    from ..models.assemblies.idealised import under_point_masses
    from ..models.rotators import MantleCore
    from .cassini import cassini_axis, peale_obliquity, precession_constant

    orbit = mean_orbit(orbits, t_start, t_end, gm)
    args = (orbit.n, orbit.e, interior.j2, interior.c22, interior.c_mr2)
    eps = peale_obliquity(*args, float(np.linalg.norm(orbit.normal_rate)), inclination)
    axis = cassini_axis(orbit.normal, orbit.normal_rate, eps + obliquity_offset)
    if eps + obliquity_offset != 0.0 and not np.linalg.norm(orbit.normal_rate):     # no precession: any azimuth
        axis = cassini_axis(orbit.normal, orbit.perihelion, eps + obliquity_offset)
    start = resonant_start(orbit, axis, interior.gamma_mantle())
    moments = interior.moments()
    core_c = (1.0 - interior.cm_over_c) * moments[2]
    rotator = MantleCore(core_c=core_c, friction=core_c / interior.coupling_time_d)
    system = under_point_masses(moments, orbits, start["q0"], start["omega0"], t_start, "resonant spin", rotator,
                                start["omega_core0"])
    return system, {"orbit": orbit, "alpha": precession_constant(*args, eps), "peale_obliquity": eps,
                    "axis": axis, "theory": start["theory"], "inclination": inclination}
