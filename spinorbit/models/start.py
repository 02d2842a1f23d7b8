"""Initial states: DE421's Moon at any epoch of its span, and a body started on a given pole on its forced motion.

* :func:`moon_de421` -- DE421's lunar mantle orientation and angular velocity at t, and its fluid core's angular
  velocity: the header gives the core at JDEPOC only (OMGCX/Y/Z), so it is carried from JDEPOC to t by the core's
  own equation (Folkner et al. 2014) driven by DE421's mantle, in inertial axes,
  d(I_c w_c)/dt = -k_v (w_c - w_m) - (C_c - A_c)(z.w_c)(z x w_c), I_c = A_c 1 + (C_c - A_c) z z^T about the
  mantle pole z, A_c = C_c (1 - COBLAT) (k_v/C_c = KVC/IFAC: 128 yr; free core precession ~200 yr), integrated by
  the classical RK4 (spinorbit.integrators) in steps of about half a day;
* :func:`earth_moon_de421` -- the same Moon with its geocentric orbit from DE421, and the Earth on a pole;
* :func:`solar_system_de421` -- every centre of a barycentric System from DE421 (the header's initial conditions
  at its epoch JDEPOC, the SPK file's states elsewhere: they agree to 1e-7 km at JDEPOC), the Moon and the Earth
  as :func:`earth_moon_de421`;
* :func:`on_pole` -- a body whose figure axis at t0 is a given pole (the Earth on the IAU pole), spinning about it
  on its forced (slow) motion: its angular momentum leads the figure axis by the Oppolzer terms
  (spinorbit.models.gyroscopic), found by fixed-point iteration, so that no free nutation starts.
"""
import math

import numpy as np

from ..base.constants import J2000_JD
from ..base.layout import Layout
from ..base.linker import cached
from ..base.rotations import cross3, dot3, quat_from_matrix
from ..bodies import de421_orientation
from ..bodies.moon import de421
from ..bodies.table import BODIES
from .ode import Ode

CORE_STEP_D = 0.25          # half the RK4 step carrying DE421's core


@cached(nogil=True)
def core_rhs(t, y, p):
    """d(I_c w_c)/dt (units of C, inertial) of the core's angular momentum y under DE421's mantle at t (module
    docstring); p = (series, start, length, k_v/C, C_c/C, A_c/C)."""
    coefficients, start, length, friction, c_c, a_c = p
    m, omega = de421_orientation.mantle(t, coefficients, start, length)
    pole = np.array([m[2, 0], m[2, 1], m[2, 2]])
    w_mantle = np.array([m[0, 0] * omega[0] + m[1, 0] * omega[1] + m[2, 0] * omega[2],
                         m[0, 1] * omega[0] + m[1, 1] * omega[1] + m[2, 1] * omega[2],
                         m[0, 2] * omega[0] + m[1, 2] * omega[1] + m[2, 2] * omega[2]])
    w = core_omega(y, pole, c_c, a_c)
    return -friction * (w - w_mantle) - (c_c - a_c) * dot3(pole, w) * cross3(pole, w)


@cached(nogil=True)
def core_omega(momentum, pole, c_c, a_c):
    """The core's angular velocity (inertial) from its angular momentum about the mantle pole."""
    return momentum / a_c - (c_c - a_c) / (a_c * c_c) * dot3(pole, momentum) * pole


def core_de421(t_tdb_d):
    """DE421's fluid-core angular velocity at TDB day t, mantle axes, rad/d (module docstring)."""
    from ..integrators import simulate

    moon = de421()
    t0, c_c = moon.epoch_tdb_d, moon.core_c_over_c
    a_c = c_c * (1.0 - moon.core_flattening)
    coefficients, (start, end) = de421_orientation.series(), de421_orientation.span()
    length = (end - start) / coefficients.shape[0]
    de421_orientation.check_span([t0, t_tdb_d])
    m0, _ = de421_orientation.mantle(t0, coefficients, start, length)
    wc = m0.T @ moon.omega_core0_rad_d                                 # inertial
    pole0 = m0[2]
    if t_tdb_d != t0:
        steps = max(1, math.ceil(abs(t_tdb_d - t0) / (2 * CORE_STEP_D)))
        momentum = a_c * wc + (c_c - a_c) * (pole0 @ wc) * pole0
        ode = Ode(core_rhs, (coefficients, start, length, moon.kv_over_c_per_d, c_c, a_c), t0, momentum,
                  Layout([("core.momentum", 3, "vector", "units of C, inertial")]), "DE421's core")
        carried, _ = simulate(ode, [t_tdb_d], "rk4", {"step": abs(t_tdb_d - t0) / steps}, estimate_error=False,
                              label="DE421's core")
        momentum = carried.y[-1]
        m_t, _ = de421_orientation.mantle(t_tdb_d, coefficients, start, length)
        wc = core_omega(momentum, np.ascontiguousarray(m_t[2]), c_c, a_c)
    m_t, _ = de421_orientation.mantle(t_tdb_d, coefficients, start, length)
    return m_t @ wc


def moon_de421(t_tdb_d, core=False):
    """DE421's Moon at TDB day t: {moon.q: body -> ICRF, moon.omega: body axes rad/d (, moon.omega_core)}."""
    de421_orientation.check_span([t_tdb_d])
    coefficients, (start, end) = de421_orientation.series(), de421_orientation.span()
    m, omega = de421_orientation.mantle(float(t_tdb_d), coefficients, start, (end - start) / coefficients.shape[0])
    state = {"moon.q": quat_from_matrix(m.T), "moon.omega": omega}
    if core:
        state["moon.omega_core"] = core_de421(float(t_tdb_d))
    return state


def frame(z, x_hint):
    """Right-handed orthonormal columns (x, y, z) with z given and x nearest ``x_hint``."""
    z = np.asarray(z, dtype=float) / np.linalg.norm(z)
    x = np.asarray(x_hint, dtype=float) - (np.asarray(x_hint, dtype=float) @ z) * z
    x /= np.linalg.norm(x)
    return np.column_stack([x, np.cross(z, x), z])


def oppolzer_axes(system, name, t, spins, states=None, step_d=1.0 / 64.0):
    """Figure axes (n, 3, inertial) of body ``name`` on its forced motion from its spin angular momenta (n, 3):
    to third order in the Oppolzer terms of the point masses acting on its figure (their tidal tensor's rates
    by central differences over ``step_d``; bodies in the state carried by their velocity): the terms of the
    gyroscopic module's docstring, every point at once."""
    from .rotators import oppolzer_attractors

    t, spins = np.atleast_1d(np.asarray(t, dtype=float)), np.atleast_2d(spins)
    figure = system.bodies[name].figure
    attractors = oppolzer_attractors(system, name)
    gm = np.array([system.motion.gm(b) for b in attractors])
    tensor, plus, minus = (tidal_tensors(np.asarray(system.motion.positions(t + dt, states, name, attractors, dt)),
                                         gm) for dt in (0.0, step_d, -step_d))
    c_minus_a = figure.c_minus_a * (1.0 + figure.anisotropy_rate_per_d * t)
    norm = np.linalg.norm(spins, axis=1)
    ell, lam = spins / norm[:, None], norm / (0.5 * (figure.moments[0] + figure.moments[1]))

    def torque(tidal, order):         # (C - A) (T ell) x ell / (|l| lam^order)
        return (c_minus_a / (norm * lam ** order))[:, None] * np.cross(np.einsum("nab,nb->na", tidal, ell), ell)

    n0, n_dot = torque(tensor, 1), torque((plus - minus) / (2 * step_d), 2)
    n_ddot = torque((plus - 2 * tensor + minus) / step_d ** 2, 3)
    z = ell - np.cross(ell, n0) - n_dot + np.cross(ell, n_ddot)
    return z / np.linalg.norm(z, axis=1)[:, None]


def tidal_tensors(rows, gm):
    """3 sum GM r r^T / r^5 (n, 3, 3) of point masses at ``rows`` (n, masses, 3) km with GM ``gm`` (masses,)
    (gyroscopic.tidal_tensor, the right-hand side's, at each of n times)."""
    s2 = np.einsum("nka,nka->nk", rows, rows)
    return np.einsum("nk,nka,nkb->nab", 3.0 * gm / (s2 * s2 * np.sqrt(s2)), rows, rows)


def forced_spin(system, name, t0, pole, spin_rate, iterations=4, states=None):
    """The spin angular momentum (3, G-scaled) of body ``name`` whose forced figure axis at t0 is ``pole`` and
    whose w.z is ``spin_rate`` (rad/d): fixed-point iteration on the Oppolzer axis (offset ~10 mas)."""
    z0 = np.asarray(pole, dtype=float) / np.linalg.norm(pole)
    c = system.bodies[name].figure.moments[2]
    ell, lc = z0.copy(), spin_rate
    for _ in range(iterations):
        ell = ell + (z0 - oppolzer_axes(system, name, [t0], [c * lc * ell], states)[0])
        ell /= np.linalg.norm(ell)
        lc = spin_rate / float(ell @ z0)                             # w_z = L.z / C
    return c * lc * ell


def on_pole(system, name, t0, pole, spin_rate, x_hint=None, forced=True, states=None):
    """{slices of body ``name``}: its figure axis at ``pole`` (inertial) spinning at ``spin_rate`` (rad/d) on its
    forced motion (or, ``forced=False``, about the figure axis, which starts a free nutation); a rotator with an
    attitude has its x axis nearest ``x_hint``."""
    spin = forced_spin(system, name, t0, pole, spin_rate, states=states) if forced else None
    if f"{name}.spin" in system.layout:
        if spin is None:
            spin = system.bodies[name].figure.moments[2] * spin_rate * np.asarray(pole) / np.linalg.norm(pole)
        return {f"{name}.spin": spin}
    moments = system.bodies[name].figure.moments
    rot = frame(pole, np.array([1.0, 0.0, 0.0]) if x_hint is None else x_hint)
    omega = rot.T @ spin / moments if forced else np.array([0.0, 0.0, spin_rate])
    return {f"{name}.q": quat_from_matrix(rot), f"{name}.omega": omega}


def earth_moon_de421(system, t0, earth_pole, spin_rate):
    """{slices}: DE421's geocentric Moon (position, velocity), lunar orientation, rates and core at t0, and the
    Earth's spin on its forced motion about ``earth_pole`` (inertial unit vector) at ``spin_rate`` (rad/d)."""
    from ..orbits.kernel import open_ephemeris

    pos, vel = open_ephemeris("de421", t0, t0).relative_states("moon", "earth", [t0])
    start = {"moon.r": pos[0], "moon.v": vel[0], **moon_de421(t0, core="moon.omega_core" in system.layout)}
    partial = system.layout.pack({**start, **on_pole(system, "earth", t0, earth_pole, spin_rate, forced=False)})
    return {**start, **on_pole(system, "earth", t0, earth_pole, spin_rate, states=partial[None])}


def solar_system_de421(system, t0, earth_pole, spin_rate, sun_spin_rate=None, others=None):
    """{slices} of a barycentric System (spinorbit.models.barycentric) at TDB day t0: every free body's and the
    Earth-Moon barycentre's barycentric state and the geocentric Moon's from DE421 (module docstring), the Moon's
    orientation, rates and core and the Earth's spin as :func:`earth_moon_de421`; a turning Sun spinning at
    ``sun_spin_rate`` (rad/d) about the IAU pole; ``others``: {slice: value} of bodies DE421 does not carry."""
    from ..bodies import sun
    from ..bodies.de421_header import header

    motion, h = system.motion, header()
    start = dict(others or {})
    for name in (n for n in (*motion.free, motion.barycentre, motion.secondary) if f"{n}.r" not in start):
        start[f"{name}.r"], start[f"{name}.v"] = _de421_state(name, t0, h)
    start.update(moon_de421(t0, core="moon.omega_core" in system.layout))
    if "sun.spin" in system.layout:
        start["sun.spin"] = system.bodies["sun"].figure.moments[2] * sun_spin_rate * sun.POLE_ICRF
    partial = system.layout.pack({**start, **on_pole(system, "earth", t0, earth_pole, spin_rate, forced=False)})
    return {**start, **on_pole(system, "earth", t0, earth_pole, spin_rate, states=partial[None])}


def _de421_state(name, t0, h):
    """(position km, velocity km/d) of ``name`` (barycentric; the Moon geocentric) at t0 from DE421."""
    if t0 == h["JDEPOC"] - J2000_JD:
        k = BODIES[name].state_key
        return (np.array([h[f"X{k}"], h[f"Y{k}"], h[f"Z{k}"]]) * h["AU"],
                np.array([h[f"XD{k}"], h[f"YD{k}"], h[f"ZD{k}"]]) * h["AU"])
    from ..orbits.kernel import open_ephemeris

    center = "earth" if name == "moon" else "solar_system_barycenter"
    pos, vel = open_ephemeris("de421", t0, t0).relative_states(name, center, [t0])
    return pos[0], vel[0]
