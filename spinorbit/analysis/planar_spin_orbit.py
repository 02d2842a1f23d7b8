"""Planar spin-orbit coupling on a Kepler ellipse (Euler ch. 16 P93-P94 with an eccentric orbit), for
the stress scenes: two realisations share the initial conditions, the full 3-D rigid body
(``rigid_body_system``, spinorbit.models.assemblies.idealised, quaternion + omega) on a ``KeplerOrbit``,
and the one-angle model (spinorbit.models.planar), used where many trajectories share one orbit
(Lyapunov maps: ``planar_lyapunov``, with analysis.lyapunov).  Times in days, angles in rad; the orbit
has periapsis on the inertial x axis and mean anomaly 0 at ``t0``.
"""
import math

import numpy as np

from ..base.rotations import matrices_from_quats
from ..integrators import simulate
from ..models.assemblies.idealised import under_point_masses
from ..models.planar import anomaly_and_distance, planar_ode, planar_rhs
from ..orbits.analytic import KeplerOrbit
from .lyapunov import benettin, compiled_flow, displaced, scipy_flow, system_flow


def kepler_orbit(gm, a, e, t0):
    """The attracting mass on a Kepler ellipse about the body, periapsis on x at t0 (TDB d)."""
    n = math.sqrt(gm / a**3)
    return KeplerOrbit(("F",), [gm], [a], [e], mean_motion=[n], mean_anomaly=[-n * t0])


def rigid_body_system(moments, orbit, t0, theta0, theta_dot0):
    """Full 3-D rigid body turning about C (= inertial z) at theta_dot0 with A at angle theta0 from
    periapsis."""
    q0 = np.array([math.cos(theta0 / 2), 0.0, 0.0, math.sin(theta0 / 2)])
    return under_point_masses(moments, orbit, q0, [0.0, 0.0, theta_dot0], t0, "planar spin-orbit")


def theta_from_quaternions(q):
    """Unwrapped angle (rad) of the body's A axis from the inertial x axis, projected on the x-y plane."""
    m = matrices_from_quats(q)
    return np.unwrap(np.arctan2(m[:, 1, 0], m[:, 0, 0]))


def forcing_coefficients(e, k_max=8, samples=4096):
    """Fourier sine coefficients S_k of (a/r)^3 sin(3M - 2f) and the mean H of (a/r)^3 cos(3M - 2f).

    Computed by quadrature over one orbit (exact to rounding for e < 0.5); for
    the 3:2 state S_1 = 1 - 11 e^2 + 959 e^4/48 + O(e^6) and H = 7e/2 - 123 e^3/16
    + O(e^5) (Peale 1972; Margot et al. 2007).  Returns (S (k_max,), H).
    """
    m = 2 * math.pi * np.arange(samples) / samples
    f, r = np.array([anomaly_and_distance(mi, e) for mi in m]).T
    s = np.sin(3 * m - 2 * f) / r**3
    c = np.cos(3 * m - 2 * f) / r**3
    k = np.arange(1, k_max + 1)
    return 2 * np.mean(s * np.sin(np.outer(k, m)), axis=1), float(np.mean(c))


def libration_theory(gamma, e):
    """{amplitude_linear, amplitude_series, w0_over_n, coefficients g_k} of the forced libration (rad) of a body in
    the 3:2 state with (B - A)/C = gamma (C: the moment that librates): the linear forced solution
    g_k = (3/2) gamma S_k / (k^2 - w0^2/n^2), w0^2/n^2 = 3 gamma H, and Margot et al. (2007)'s series
    (3/2) gamma (1 - 11 e^2 + 959 e^4/48) of its 88-d term."""
    s, h = forcing_coefficients(e, 24)
    w0_over_n2 = 3 * gamma * h
    k = np.arange(1, s.size + 1)
    g = 1.5 * gamma * s / (k**2 - w0_over_n2)
    return {"g": g, "w0_over_n": math.sqrt(w0_over_n2), "amplitude_linear": float(g[0]),
            "amplitude_series": 1.5 * gamma * (1 - 11 * e**2 + 959 * e**4 / 48), "S1": float(s[0]), "H": h}


def planar_lyapunov(p, theta0, rate0, t0, period, orbits, steps, d0, method="rk8"):
    """Running exponents (orbits, n_starts) in 1/T for starts theta0, rate0 (rad, rad/d): all starts and
    neighbours in one vector of planar_rhs copies; ``method`` "rk8" (``steps`` per period) or "dop853"."""
    theta0, rate0 = np.broadcast_arrays(np.atleast_1d(theta0).astype(float),
                                        np.atleast_1d(rate0).astype(float))
    scale = np.array([1.0, p[0]])
    advance = (compiled_flow(planar_rhs, p, t0, period, period / steps) if method == "rk8"
               else scipy_flow(planar_rhs, p, t0, period))
    return benettin(advance, displaced(np.column_stack([theta0, rate0]), d0, scale), d0, orbits, scale)


def rigid_body_lyapunov(system, period, orbits, steps, d0):
    """Running exponent (orbits,) in 1/T of a 3-D SpinSystem, distance |(2 dq, d omega/n)|."""
    scale = np.array([0.5] * 4 + [2 * math.pi / period] * 3)
    advance = system_flow(system, period, "rk8", step=period / steps)
    return benettin(advance, displaced(system.y0, d0, scale), d0, orbits, scale)[:, 0]


def planar_vs_rigid_body(moments, orbit, p, t0, period, start):
    """(max |theta_planar - theta_3D| (rad) over 5 orbits, the 3-D SpinSystem) from
    start = (theta - f, theta'/n) at periapsis: the planar model against the 3-D body of ``moments`` kept
    in the plane."""
    n = p[0]
    t = t0 + np.linspace(0.0, 5 * period, 501)
    system = rigid_body_system(moments, orbit, t0, start[0], start[1] * n)
    body = simulate(system, t, "rk8", {"step": period / 512}, estimate_error=False)[0]
    planar = simulate(planar_ode(p, t0, start[0], start[1] * n), t, "rk8", {"step": period / 512},
                      estimate_error=False)[0].y
    return float(np.abs(theta_from_quaternions(body.quaternion) - planar[:, 0]).max()), system
