"""One entry point: the perturbers' orbits relative to the spinning body, built once per run.

``sample_orbits("de421", "moon", ("earth", "sun"), t0, t1)`` samples the ephemeris
on a uniform grid into a :class:`HermiteOrbits` and measures its interpolation
error at every mid-point (``max_error_km``, ``max_relative_error`` per body).
"""
import numpy as np

from ..constants import GM_KM3_D2
from ..errors import InputError

# Common grid step, days.  Quintic Hermite, measured over 2000-2001 (max at mid-points,
# |dr|/r): Moon-centred Earth 0.25 d 3.7e-12, Moon-centred Sun 0.25 d 8.7e-15 (the cubic
# Hermite used before: 5.6e-8 and 1.3e-10).  One 0.25-d grid for a Moon-centred run.
DEFAULT_STEP_D = 0.25
SOURCES = "'de421', a .bsp name in ephemerides/ (e.g. 'de440'), 'rebound', 'circular', 'kepler'"


def gm_of(bodies, table=GM_KM3_D2):
    """GM of each body, km^3/day^2 (DE421 values)."""
    unknown = [b for b in bodies if b not in table]
    if unknown:
        raise InputError("bodies", unknown, f"bodies with a known GM: {sorted(table)}")
    return np.array([table[b] for b in bodies])


def sample_orbits(source, center, bodies, t_start, t_end, step=None, measure=True):
    """``bodies`` relative to ``center`` over [t_start, t_end] TDB days, as an OrbitSource.

    source: 'de421' (skyfield-data .bsp; de421 package arrays beyond 2053), any
    '<name>' with ephemerides/<name>.bsp or naif-<name> installed, 'rebound'
    (N-body from DE421 states at t_start), or 'circular' / 'kepler' (the two-body
    orbit through DE421's state at t_start; returned unsampled, exact).
    """
    bodies = tuple(bodies)
    step = DEFAULT_STEP_D if step is None else float(step)
    if source in ("circular", "kepler"):
        return two_body_orbits(source, center, bodies, t_start)
    if source == "rebound":
        orbits = rebound_orbits(center, bodies, t_start, t_end, step)
        reference = None
    elif isinstance(source, str):
        from .interpolant import HermiteOrbits, grid
        from .kernel import open_ephemeris

        ephemeris = open_ephemeris(source, t_start, t_end)
        times = grid(t_start, t_end, step)
        ephemeris.check_span(times[0], times[-1])

        def reference(t):
            return np.stack([ephemeris.relative_states(b, center, t)[0] for b in bodies], axis=1)

        states = [ephemeris.relative_states(b, center, times) for b in bodies]
        for body, (pos, vel) in zip(bodies, states):
            if not (np.isfinite(pos).all() and np.isfinite(vel).all()):
                raise InputError("source", source, f"a kernel with finite coefficients ({body} relative "
                                                            f"to {center} is not finite in kernel {ephemeris.name!r})")
        orbits = HermiteOrbits(bodies, gm_of(bodies), t_start, step, [s[0] for s in states],
                               [s[1] for s in states], source=ephemeris.name)
    else:
        raise InputError("source", source, SOURCES)
    if measure and reference is not None:
        orbits.measure_error(reference)
        if orbits.jump is not None:
            body, t, err, typical = orbits.jump
            raise InputError("source", source,
                                f"a kernel whose bodies move smoothly: {bodies[body]} relative to {center} jumps "
                                f"near t = {t:.6g} d TDB from J2000 (interpolation error {err:.3g} km there, "
                                f"{typical:.3g} km typical)")
    return orbits


def two_body_orbits(kind, center, bodies, t_epoch, kernel=None):
    """Kepler ellipses (or circles) through the DE421 states of ``bodies`` at t_epoch (TDB d).

    Each body moves about ``center`` under GM(center) + GM(body).  'kepler' takes the
    osculating elements; 'circular' keeps the orbit plane, the current distance and
    the current position in the plane, with e = 0 (Euler's hypothesis, §825).
    """
    from .analytic import KeplerOrbit
    from .kernel import JPLKernel

    kernel = JPLKernel() if kernel is None else kernel
    mu = gm_of(bodies) + gm_of((center,))
    rows = [_elements(*kernel.relative_states(b, center, [t_epoch]), m, kind == "circular")
            for b, m in zip(bodies, mu)]
    a, e, incl, node, peri, m0 = np.array(rows).T
    n = np.sqrt(mu / a**3)
    return KeplerOrbit(bodies, gm_of(bodies), a, e, n, m0 - n * t_epoch, peri, incl, node)


def _elements(r, v, mu, circular=False):
    """(a, e, inclination, node, argument of periapsis, mean anomaly) of a state (km, km/d).

    circular: (|r|, 0, i, node, 0, argument of latitude) instead.
    """
    r, v = r[0], v[0]
    h_hat = np.cross(r, v) / np.linalg.norm(np.cross(r, v))
    node_vec = np.cross([0.0, 0.0, 1.0], h_hat)
    n_hat = node_vec / np.linalg.norm(node_vec) if np.linalg.norm(node_vec) > 1e-12 else np.array([1.0, 0, 0])
    m_hat = np.cross(h_hat, n_hat)
    incl, node = np.arccos(h_hat[2]), np.arctan2(n_hat[1], n_hat[0])
    if circular:
        return np.linalg.norm(r), 0.0, incl, node, 0.0, np.arctan2(r @ m_hat, r @ n_hat)
    e_vec = np.cross(v, np.cross(r, v)) / mu - r / np.linalg.norm(r)
    e = np.linalg.norm(e_vec)
    a = 1.0 / (2.0 / np.linalg.norm(r) - v @ v / mu)
    peri = np.arctan2(e_vec @ m_hat, e_vec @ n_hat)
    nu = np.arctan2(np.cross(e_vec, r) @ h_hat, e_vec @ r)
    big_e = 2.0 * np.arctan(np.sqrt((1 - e) / (1 + e)) * np.tan(nu / 2))
    return a, e, incl, node, peri, big_e - e * np.sin(big_e)


def barycentric(source, names, t_start, t_end, step_d=1.0):
    """``names`` (bodies and barycentres, e.g. "earth_moon_barycenter") relative to the solar system's barycentre,
    sampled every ``step_d`` days over [t_start, t_end] TDB days into a HermiteOrbits of states.

    source: a JPL ephemeris ("de421", "de440", a .bsp name) or "rebound" (spinorbit.orbits.nbody: an N-body run of
    the Sun, the planets, Pluto, the Earth and the Moon from DE421's state, the barycentre from its Earth and Moon;
    for spans or epochs no ephemeris covers).  A barycentre's GM is 0 here: it is where a pair sits, not a mass."""
    from ..bodies.de421_header import gm_km3_d2
    from .interpolant import HermiteOrbits, grid
    from .kernel import open_ephemeris

    if not isinstance(source, str) or source in ("circular", "kepler"):
        raise InputError("source", source, "'de421', another JPL ephemeris ('de440', a .bsp name), or 'rebound'")
    if source == "rebound":
        orbits = rebound_orbits(None, names, t_start, t_end, step_d)
        orbits.gm = np.array([0.0 if name.endswith("barycenter") else g for name, g in zip(names, orbits.gm)])
        return orbits
    t = grid(t_start, t_end, step_d)
    ephemeris = open_ephemeris(source, t[0], t[-1])
    states = [ephemeris.relative_states(name, "solar_system_barycenter", t) for name in names]
    gm = [0.0 if name.endswith("barycenter") else gm_km3_d2(name) for name in names]
    return HermiteOrbits(names, gm, t[0], step_d, np.array([s[0] for s in states]),
                         np.array([s[1] for s in states]), source=ephemeris.name)


def rebound_days(t_start, t_end):
    """Days REBOUND integrates for :func:`rebound_orbits` over [t_start, t_end]: out from DE421's nearest epoch,
    then over the span."""
    from .kernel import DE421Arrays

    first, last = DE421Arrays().span
    return abs(t_start - float(np.clip(t_start, first, last))) + abs(t_end - t_start)


def rebound_orbits(center, names, t_start, t_end, step):
    """A REBOUND run (spinorbit.orbits.nbody) sampled over [t_start, t_end], started from DE421's states at
    t_start, or at the nearest epoch DE421 covers and integrated out from there."""
    from .kernel import DE421Arrays, open_ephemeris
    from .nbody import ReboundOrbits

    first, last = DE421Arrays().span
    epoch = float(np.clip(t_start, first, last))
    return ReboundOrbits(center, names, t_start, t_end, step, kernel=open_ephemeris("de421", epoch, epoch),
                         epoch=epoch)
