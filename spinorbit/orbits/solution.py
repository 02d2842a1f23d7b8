"""The Earth's orbit over millions of years: the solar system integrated by REBOUND from a JPL ephemeris's
state at J2000, written once to a file with its provenance and reused by every run needing a span it covers.

Model: the Sun, Mercury to Neptune (system barycentres), Pluto and the Earth-Moon barycentre (EMB), DE421's
GMs, integrated by WHFast (Wisdom & Holman 1991; Rein & Tamayo 2015) in Jacobi coordinates with 11th-order
symplectic correctors; the Sun's relativity by REBOUNDx ``gr_potential`` (Nobili & Roxburgh 1986: 1PN's
perihelion advance, not velocity-dependent, so the map stays symplectic); the Moon as the EMB's orbit-averaged
quadrupole (REBOUNDx ``gravitational_harmonics`` on the EMB, its axis the EMB's orbit normal, reset at every
output: the lunar orbit regresses about the ecliptic in 18.6 yr).  Seen from afar the Earth and the Moon are a
ring of the Moon's orbit, J2 R^2 = nu <rho^2> / 2 (1 - 3/2 sin^2 i_m), nu = m_E m_M / (m_E + m_M)^2,
<rho^2> = a_m^2 (1 + 3/2 e_m^2) ("static_ring"), which advances the EMB's perihelion by ~0.08"/yr (GR:
0.04"/yr) and leaves its node alone; "ring" (the default) takes MOON's measured share of it; "none": a point
mass.

Outputs every ``output_d`` (a multiple of the step, so that outputs fall on steps): the heliocentric osculating
orbit normal, eccentricity vector (ICRF axes, the ephemeris's) and semi-major axis of each body of ``OUTPUTS``
(the EMB, Mars: the bodies whose spin deep time follows), TDB days from J2000, ascending.  The two branches
(backward and forward from J2000) keep their last state, so a file is extended bit for bit; it is written every
``SAVE_EVERY_S`` and when a run stops, and reloaded by the next.

A file is input like any other, kept in the verified room (spinorbit.base.verified): opened only when it is a regular
file, read without pickles, and used only when every array it holds (the outputs, the settings and the end states
each branch continues from) matches the sha256 it carries and its record is these settings'; anything else is
refused in one line (not remade: the file may hold hours of integration; delete it to recompute).  Leftovers of a
save that was killed are removed.
"""
import ast
import contextlib
import functools
import hashlib
import inspect
import json
import os
import sys
import textwrap
import time
import zipfile
import zlib
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np

from ..base import verified
from ..base.constants import DAY_S
from ..base.errors import InputError
from ..base.files import NotRegular, open_regular
from ..base.linker import cache
from ..base.progress import progress
from ..bodies import moon
from ..bodies.de421_header import header
from ..bodies.table import gm_km3_d2, heliocentric_set
from .interrupts import python_sigint

BODIES = heliocentric_set()
SUN, EMB = BODIES.index("sun"), BODIES.index("earth_moon_barycenter")
OUTPUTS = ("earth_moon_barycenter", "mars")     # the bodies whose heliocentric orbits a solution keeps
FORMAT = 3                      # the file's layout: every array covered by its hash
SAVE_EVERY_S = 30.0
POLL_S = 5.0
# The Moon's orbit-averaged quadrupole on the EMB, as a factor of the static ring's (``lunar_ring_j2``):
# "ring" takes the lunar orbit's response to the solar tide into account, measured as the EMB's perihelion
# drift of a run with the Moon as a body (IAS15, DE421's Moon, 3 kyr; benchmarks/bench_deep_time.py moon):
# 0.859.
# The static ring over DE421's Moon averages rho^2 P2(cos gamma) to 0.958 of it; the rest is dynamical.
MOON = {"ring": 0.859, "static_ring": 1.0, "none": 0.0}


@dataclass(frozen=True)
class Settings:
    """What decides a solution: ephemeris of the J2000 state, WHFast step and output cadence (days), the Sun's
    relativity, the Moon ("ring" or "none"), and a relative displacement of the EMB's starting position (to
    measure the chaos)."""

    ephemeris: str = "de421"
    step_d: float = 5.0
    output_d: float = 36525.0
    relativity: bool = True
    moon: str = "ring"
    displacement: float = 0.0

    def check(self):
        if self.moon not in MOON:
            raise InputError("moon", self.moon, f"one of {sorted(MOON)}")
        if not 0 < self.step_d <= 20:
            raise InputError("step", self.step_d, "a WHFast step in (0, 20] days (Mercury's orbit is 88 d)")
        ratio = self.output_d / self.step_d
        if not (ratio >= 1 and ratio == round(ratio)):
            raise InputError("output", self.output_d, f"a whole number of WHFast steps of {self.step_d:g} d")

    def record(self):
        """The settings and everything else that decides the numbers (library versions, the integration's
        code)."""
        import rebound
        import reboundx

        return {**asdict(self), "format": FORMAT, "bodies": list(BODIES), "moon_j2": MOON[self.moon] * lunar_ring_j2(),
                "rebound": rebound.__version__,
                "reboundx": reboundx.__version__, "integration_source": integration_digest()}

    def key(self):
        return hashlib.sha256(json.dumps(self.record(), sort_keys=True).encode()).hexdigest()[:20]


@functools.cache
def integration_digest():
    """Hash of the code that computes the numbers (the run, the ring, the start) as Python parses it, its
    docstrings, comments and layout aside: a changed integration never reuses an old file."""
    digest = hashlib.sha256()
    for part in (_ReboundBranch, lunar_ring_j2, _ephemeris_states):
        tree = ast.parse(textwrap.dedent(inspect.getsource(part)))
        for node in ast.walk(tree):
            body = getattr(node, "body", None)
            if isinstance(body, list) and body and isinstance(body[0], ast.Expr) and isinstance(
                    getattr(body[0], "value", None), ast.Constant) and isinstance(body[0].value.value, str):
                node.body = body[1:] or [ast.Pass()]
        digest.update(ast.dump(tree).encode())
    return digest.hexdigest()[:16]


def cache_directory():
    """Where solutions are kept: ``<spinorbit's private cache>/orbital_solutions`` (spinorbit.base.verified.folder)."""
    return verified.folder("orbital_solutions")


@dataclass(frozen=True)
class HeliocentricOrbit:
    """One body's heliocentric osculating orbit at a solution's times: ``normal`` and ``eccentricity_vector``
    (k, 3) in ICRF axes, ``semi_major_axis_km`` (k,)."""

    normal: np.ndarray
    eccentricity_vector: np.ndarray
    semi_major_axis_km: np.ndarray

    @property
    def eccentricity(self):
        return np.linalg.norm(self.eccentricity_vector, axis=1)


ORBIT_ARRAYS = ("normal", "eccentricity_vector", "semi_major_axis_km")


class OrbitalSolution:
    """The heliocentric orbits of OUTPUTS at ``t_d`` (ascending TDB days from J2000): ``orbits`` {body:
    HeliocentricOrbit} (``of(body)``; ``normal``, ``eccentricity_vector``, ``semi_major_axis_km`` and
    ``eccentricity`` are the EMB's); ``ends``: {"backward", "forward"}: (t, states (n_bodies, 6)) where each
    branch stopped; ``record``: the settings; ``provenance``: how it was made."""

    def __init__(self, t_d, orbits, ends, record, provenance):
        self.t_d, self.orbits, self.ends = t_d, orbits, ends
        self.record, self.provenance = record, provenance

    def of(self, body):
        """The HeliocentricOrbit of ``body`` (one of OUTPUTS)."""
        if body not in self.orbits:
            raise InputError("body", body, f"a body whose orbit the solution keeps: {list(self.orbits)}")
        return self.orbits[body]

    @property
    def span(self):
        return float(self.t_d[0]), float(self.t_d[-1])

    @property
    def normal(self):
        return self.orbits[BODIES[EMB]].normal

    @property
    def eccentricity_vector(self):
        return self.orbits[BODIES[EMB]].eccentricity_vector

    @property
    def semi_major_axis_km(self):
        return self.orbits[BODIES[EMB]].semi_major_axis_km

    @property
    def eccentricity(self):
        return self.orbits[BODIES[EMB]].eccentricity

    def covers(self, t_start, t_end):
        return self.span[0] <= min(t_start, t_end) and max(t_start, t_end) <= self.span[1]

    def elements(self, rotation):
        """(e, varpi, i, Omega) rad, in the frame whose axes are the rows of ``rotation`` (ICRF -> frame)."""
        return elements(self.normal, self.eccentricity_vector, rotation)

    def arrays(self):
        """{name: array} of everything the file holds but the record and the provenance."""
        ends = {f"end_{name}_{part}": value for name, (t, states) in self.ends.items()
                for part, value in (("t", np.float64(t)), ("states", np.asarray(states)))}
        orbits = {f"{body}_{name}": getattr(orbit, name) for body, orbit in self.orbits.items()
                  for name in ORBIT_ARRAYS}
        return {"t_d": self.t_d, **orbits, **ends}

    def save(self, path):
        """Write atomically, every array hashed (spinorbit.base.verified.write)."""
        verified.write(path, self.arrays(), self.record, {**self.provenance, "span_d": list(self.span)})

    @classmethod
    def load(cls, path, record):
        """The solution in ``path``; InputError (one line) unless it was made with ``record`` and is
        intact."""
        accepted = "an orbital solution file of these settings (delete it, or name another, to recompute)"
        try:
            entry = verified.read(path)
            if entry is None:
                raise FileNotFoundError(2, "No such file or directory")
            held, stored, provenance = entry.arrays, entry.record, entry.meta
            ends = {name: (float(held[f"end_{name}_t"]), held[f"end_{name}_states"])
                    for name in ("backward", "forward") if f"end_{name}_t" in held}
            orbits = {body: HeliocentricOrbit(*(held[f"{body}_{name}"] for name in ORBIT_ARRAYS))
                      for body in OUTPUTS}
            solution = cls(held["t_d"], orbits, ends, stored, provenance)
        except verified.Damaged as exc:
            raise InputError("orbit_file", str(path), f"{accepted}; {exc}") from None
        except (OSError, KeyError, ValueError) as exc:
            reason = (exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc).splitlines()[0]
                      if str(exc) else type(exc).__name__)
            raise InputError("orbit_file", str(path), f"{accepted} ({type(exc).__name__}: {reason})") from None
        differ = sorted(k for k in set(stored) | set(record) if stored.get(k) != record.get(k))
        if differ:
            detail = ", ".join(f"{k} {stored.get(k)!r} (this run: {record.get(k)!r})" for k in differ)
            raise InputError("orbit_file", str(path), f"{accepted}; it differs in {detail}")
        if set(held) != set(solution.arrays()):
            raise InputError("orbit_file", str(path), f"{accepted}; it holds {sorted(held)}")
        return solution


def elements(normal, eccentricity_vector, rotation):
    """(e, varpi, i, Omega) rad of orbits given by their normals and eccentricity vectors (k, 3, ICRF), in the
    frame whose axes are the rows of ``rotation``: varpi = Omega + omega, the longitude of perihelion measured
    along the frame's plane to the node, then along the orbit."""
    n, ev = normal @ rotation.T, eccentricity_vector @ rotation.T
    node = np.arctan2(n[:, 0], -n[:, 1])
    to_node = np.column_stack([np.cos(node), np.sin(node), np.zeros_like(node)])
    perihelion = np.arctan2(np.sum(np.cross(to_node, ev) * n, axis=1), np.sum(to_node * ev, axis=1))
    incl = np.arctan2(np.hypot(n[:, 0], n[:, 1]), n[:, 2])
    return (np.linalg.norm(ev, axis=1), np.mod(node + perihelion, 2 * np.pi), incl, np.mod(node, 2 * np.pi))


def file_name(settings):
    """The cache's file of a solution of ``settings``."""
    return f"{settings.ephemeris}-{settings.key()}.npz"


def steps_to_compute(settings, t_start, t_end, path=None):
    """WHFast steps a :func:`solve` over [t_start, t_end] still has to take: those beyond the span that the file
    (default: the cache's for these settings) covers, all of them when there is none or it cannot be read."""
    lo, hi = min(t_start, t_end, 0.0), max(t_start, t_end, 0.0)
    path = Path(path) if path else cache.root() / "orbital_solutions" / file_name(settings)
    try:
        with open_regular(path) as f, np.load(f, allow_pickle=False) as data:
            t_d = data["t_d"]
            covered = (float(t_d[0]), float(t_d[-1]))
    except (OSError, ValueError, KeyError, IndexError, EOFError, zipfile.BadZipFile, zlib.error):
        covered = (0.0, 0.0)
    return (max(0.0, covered[0] - lo) + max(0.0, hi - covered[1])) / settings.step_d


def solve(settings, t_start, t_end, path=None, label="orbital solution"):
    """The solution covering [t_start, t_end] TDB days (J2000 inside it): read from ``path`` (default: the
    cache file of these settings) and extended as needed, computed when there is none.  One process at a time
    works on a file (a lock); the others wait and read what it wrote."""
    settings.check()
    record = settings.record()
    if path is None:
        path = cache_directory() / file_name(settings)
    path = Path(path)
    lo, hi = min(t_start, t_end, 0.0), max(t_start, t_end, 0.0)
    said = False
    while True:
        try:
            with _locked(path):
                verified.remove_leftovers(path)
                solution = OrbitalSolution.load(path, record) if os.path.lexists(path) else None
                if solution is None or not solution.covers(lo, hi):
                    solution = _extend(solution, settings, record, lo, hi, path, label)
            break
        except verified.Busy:            # another process is extending it: use its file once long enough
            if os.path.lexists(path) and (solution := OrbitalSolution.load(path, record)).covers(lo, hi):
                break
            if not said:
                print(f"waiting for another process computing {path}", file=sys.stderr)
                said = True
            time.sleep(POLL_S)
    solution.path = path
    return solution


@contextlib.contextmanager
def _locked(path):
    """Hold the lock beside ``path`` (verified.lock, not waited on: Busy) if it is a regular file (or none yet): a
    FIFO there never blocks, a missing folder is one line."""
    held = verified.lock(path, wait_s=0, repair=False)
    try:
        held.__enter__()
    except NotRegular:
        raise InputError("orbit_file", str(path), "a regular file beside a regular lock file (its .lock is not)") \
            from None
    except OSError as exc:
        raise InputError("orbit_file", str(path), f"a file in a folder you can write ({exc.strerror})") from None
    try:
        yield
    finally:
        held.__exit__(None, None, None)


def _extend(solution, settings, record, lo, hi, path, label):
    """Integrate each branch from where it stopped (or from the ephemeris at J2000) out to lo and hi, writing
    the file every SAVE_EVERY_S and when the run stops."""
    sign = {"backward": -1.0, "forward": 1.0}
    target = {"backward": lo, "forward": hi}
    rows = {"backward": [], "forward": []}          # (t, each output's normal, e vector, a) from J2000 outward
    ends = {} if solution is None else dict(solution.ends)
    if solution is not None:
        table = np.column_stack([solution.t_d, *(getattr(solution.of(body), name) for body in OUTPUTS
                                                 for name in ORBIT_ARRAYS)])
        j2000 = int(np.searchsorted(solution.t_d, 0.0))
        rows = {"backward": list(table[:j2000 + 1][::-1]), "forward": list(table[j2000:])}
    earlier = 0.0 if solution is None else solution.provenance.get("wall_s", 0.0)
    started = saved = time.perf_counter()

    def todo(name):
        return not rows[name] or sign[name] * (target[name] - rows[name][-1][0]) > 0

    def current():
        table = np.array(rows["backward"][::-1] + rows["forward"][1 if rows["backward"] else 0:])
        provenance = {"wall_s": earlier + time.perf_counter() - started, **_describe(settings)}
        orbits = {body: HeliocentricOrbit(table[:, 1 + 7 * k:4 + 7 * k], table[:, 4 + 7 * k:7 + 7 * k],
                                          table[:, 7 + 7 * k]) for k, body in enumerate(OUTPUTS)}
        return OrbitalSolution(table[:, 0], orbits, dict(ends), record, provenance)

    total = sum(abs(target[n] - (rows[n][-1][0] if rows[n] else 0.0)) for n in rows if todo(n)) / 365250.0
    try:
        with progress(label, 0.0, total, unit="kyr") as advance_to:
            done = 0.0
            for name in [n for n in rows if todo(n)]:
                run = _ReboundBranch(settings, ends.get(name), sign[name])
                if not rows[name]:
                    rows[name].append(run.output())
                first = rows[name][-1][0]
                while todo(name):
                    rows[name].append(run.advance())
                    ends[name] = run.state()
                    advance_to(done + abs(rows[name][-1][0] - first) / 365250.0)
                    if time.perf_counter() - saved > SAVE_EVERY_S:
                        current().save(path)
                        saved = time.perf_counter()
                done += abs(rows[name][-1][0] - first) / 365250.0
    except BaseException:
        if rows["backward"] or rows["forward"]:
            current().save(path)
            print(f"orbital solution so far saved in {path}; the next run continues from it", file=sys.stderr)
        raise
    current().save(path)
    return OrbitalSolution.load(path, record)


def _describe(settings):
    return {"integrator": f"REBOUND WHFast (Jacobi, corrector 11), step {settings.step_d:g} d",
            "forces": "Newtonian point masses"
            + (", Sun's GR (REBOUNDx gr_potential)" if settings.relativity else "")
            + (f", the Moon as the EMB's orbit-averaged quadrupole ({settings.moon}: "
               f"{MOON[settings.moon]} of the static ring, REBOUNDx gravitational_harmonics)"
               if MOON[settings.moon] else ""),
            "bodies": ", ".join(BODIES) + " (DE421's GMs)",
            "start": f"{settings.ephemeris} barycentric states at J2000 (TDB)",
            "output": f"the heliocentric osculating orbits of {', '.join(OUTPUTS)} every "
                      f"{settings.output_d:g} d, ICRF axes"}


class _ReboundBranch:
    """One branch: a REBOUND simulation from J2000 (the ephemeris) or from a stored state, stepping by
    ``direction`` x step to the next output."""

    def __init__(self, settings, end, direction):
        import rebound
        import reboundx

        self.settings = settings
        gm = [gm_km3_d2(b) if b != BODIES[EMB] else gm_km3_d2("earth") + gm_km3_d2("moon") for b in BODIES]
        t0, states = end if end is not None else (0.0, _ephemeris_states(settings))
        sim = rebound.Simulation()
        sim.G = 1.0
        for m, state in zip(gm, states):
            sim.add(m=m, x=state[0], y=state[1], z=state[2], vx=state[3], vy=state[4], vz=state[5])
        sim.t = t0
        sim.integrator = "whfast"
        sim.integrator.corrector = 11
        sim.integrator.safe_mode = 0
        sim.dt = direction * settings.step_d
        extras = reboundx.Extras(sim)
        if settings.relativity:
            gr = extras.load_force("gr_potential")
            extras.add_force(gr)
            gr.params["c"] = header()["CLIGHT"] * DAY_S
        if MOON[settings.moon]:
            ring = extras.load_force("gravitational_harmonics")
            extras.add_force(ring)
            sim.particles[EMB].params["J2"] = MOON[settings.moon] * lunar_ring_j2()
            sim.particles[EMB].params["R_eq"] = moon.MEAN_DISTANCE_KM
        self.sim, self.extras, self.direction, self.vec3d = sim, extras, direction, rebound.Vec3d
        self._orient()

    def _orient(self):
        if MOON[self.settings.moon]:
            self.sim.particles[EMB].params["Omega"] = self.vec3d(*self.elements(EMB)[0])

    def elements(self, index):
        """Body ``index``'s heliocentric (normal, eccentricity vector, semi-major axis km)."""
        p = self.sim.particles
        sun, body = p[SUN], p[index]
        r = np.array([body.x - sun.x, body.y - sun.y, body.z - sun.z])
        v = np.array([body.vx - sun.vx, body.vy - sun.vy, body.vz - sun.vz])
        mu = sun.m + body.m
        h = np.cross(r, v)
        distance = np.linalg.norm(r)
        return h / np.linalg.norm(h), np.cross(v, h) / mu - r / distance, 1.0 / (2.0 / distance - v @ v / mu)

    def output(self):
        """(t, then each of OUTPUTS' normal, eccentricity vector, semi-major axis)."""
        return np.array([self.sim.t, *(x for body in OUTPUTS for normal, ecc, a in
                                       [self.elements(BODIES.index(body))] for x in (*normal, *ecc, a))])

    def advance(self):
        """Step to the next output (outputs fall on steps) and synchronise; the ring's axis follows the orbit.
        The first step after an output is taken in WHFast's safe mode, which starts from the particles: a run
        continued from a stored output then steps exactly as one that never stopped."""
        self.sim.integrator.safe_mode = 1
        with python_sigint():
            self.sim.steps(1)
        self.sim.integrator.safe_mode = 0
        with python_sigint():
            self.sim.integrate(self.sim.t + self.direction * (self.settings.output_d - self.settings.step_d),
                               exact_finish_time=0)
        self.sim.synchronize()
        self._orient()
        return self.output()

    def state(self):
        p = self.sim.particles
        return self.sim.t, np.array([[q.x, q.y, q.z, q.vx, q.vy, q.vz] for q in p])


def lunar_ring_j2():
    """J2 (at R_eq = the Moon's mean distance) of the Earth-Moon pair averaged over the lunar orbit and its
    nodal regression: nu (1 + 3/2 e_m^2)(1 - 3/2 sin^2 i_m) / 2, nu = m_E m_M / (m_E + m_M)^2."""
    earth, moon_gm = gm_km3_d2("earth"), gm_km3_d2("moon")
    nu = earth * moon_gm / (earth + moon_gm) ** 2
    i = np.radians(moon.MEAN_INCLINATION_DEG)
    return 0.5 * nu * (1 + 1.5 * moon.MEAN_ECCENTRICITY**2) * (1 - 1.5 * np.sin(i) ** 2)


def _ephemeris_states(settings):
    """Barycentric states (n_bodies, 6), km and km/d, of BODIES at J2000 from the ephemeris; the EMB displaced
    by ``settings.displacement`` of its heliocentric position."""
    from .kernel import open_ephemeris

    kernel = open_ephemeris(settings.ephemeris, 0.0, 0.0)
    states = np.array([np.concatenate([x[0] for x in kernel.relative_states(body, "solar_system_barycenter",
                                                                            [0.0])]) for body in BODIES])
    states[EMB, :3] += settings.displacement * (states[EMB, :3] - states[SUN, :3])
    return states
