"""What an exported SPK holds: one track (an SPK segment) per body, its positions about a centre as Chebyshev
series on records of the body's own length and degree, as JPL lays DE421 out (its segments: Mercury 8 d,
degree 13; Venus, the Sun and the Earth-Moon barycentre 16 d; Mars to Pluto 32 d, degree 5-10; the Moon and
the Earth about their barycentre 4 d), so a slow planet is not written on the Moon's 4-d grid.

A track is refitted from the solution's series (or, for the coupled Earth-Moon's barycentre, which the
solution does not integrate, from the run's ephemeris) by interpolation at each record's Chebyshev points
(solutions.chebyshev) and checked against what it was fitted to at the extrema of T_(n+1) between them: that
difference is the track's stated fit error.  Records tile the export's span exactly, each a whole number of
the solution's segments (record_count: the body's length where the span allows, else shorter; for the
scene's 1950-2050, 9132 segments of 4 d, Mars to Pluto get 24 d).  The Moon and the Earth about their
barycentre keep the solution's own series.
"""
from dataclasses import dataclass

import numpy as np

from ..bodies.table import BODIES, EMB, gm_km3_d2
from .chebyshev import Segments, interpolating_at

# (longest record d, degree) of each body's track: DE421's lengths, the degree the least (with one to spare)
# whose refit of the solution's series holds 1 mm, or the rounding floor of positions of its size, (n + 1) eps
# |r| (Saturn to Pluto: 2-7 mm), measured over 1950-2050 (benchmarks/bench_solutions.py export).
RECORDS = {"sun": (16.0, 10), "mercury": (8.0, 13), "venus": (16.0, 11), EMB: (16.0, 13), "mars": (32.0, 12),
           "jupiter": (32.0, 8), "saturn": (32.0, 6), "uranus": (32.0, 6), "neptune": (32.0, 6),
           "pluto": (32.0, 6)}


@dataclass
class Track:
    """One SPK segment: ``target`` about ``centre`` (NAIF codes), ``name``; ``segments``: its records (km);
    ``fit_error_km``: the largest difference of the records from what they were fitted to (0: the solution's
    own series); ``source``: what they were fitted to."""

    target: int
    centre: int
    name: str
    segments: Segments
    fit_error_km: float
    source: str


def body_code(body):
    """The NAIF code of a body's own centre (the planet, not its system): the first of the table's codes."""
    return BODIES[body].naif[0]


def position_code(body):
    """The NAIF code of what an integrated point mass is: its system's barycentre (the table's last code)."""
    return BODIES[body].naif[-1]


def tracks(solution):
    """[Track] of the solution's ``<body>.r`` slices: a barycentric body about 0 on its RECORDS (refitted); the
    Moon seen from the Earth as the Moon and the Earth about their barycentre (3), (1 - mu) r and -mu r with
    mu = GM_moon / (GM_earth + GM_moon) of the body table, on the solution's own series -- with, when the
    solution carries no barycentric bodies (the coupled Earth-Moon), their barycentre about 0 read from the run's
    ephemeris, so that the file alone reaches the solar-system barycentre; another body seen from another,
    about it."""
    out, own = [], solution.segments
    barycentric = [p for p in solution.layout.slices if p.name.endswith(".r") and "barycentric" in p.unit]
    for part in solution.layout.slices:
        if not part.name.endswith(".r"):
            continue
        body = part.name[:-2]
        series = Segments(own.origin_d, own.length_d, own.first, own.coefficients[:, part.index, :])
        if part in barycentric:
            length, degree = RECORDS.get(body, (own.length_d, own.degree))
            segments, error = refitted(series.evaluate, solution.span, record_count(own, length), degree)
            out.append(Track(position_code(body), 0, body, segments, error, "the solution"))
            continue
        primary = part.unit.split("from ")[1].split(",")[0]
        if (primary, body) == ("earth", "moon"):
            mu = gm_km3_d2("moon") / (gm_km3_d2("earth") + gm_km3_d2("moon"))
            out += [Track(body_code("moon"), position_code(EMB), "moon", scaled(series, 1.0 - mu), 0.0,
                          "the solution"),
                    Track(body_code("earth"), position_code(EMB), "earth", scaled(series, -mu), 0.0, "the solution")]
            if not barycentric:
                out.append(barycentre_track(solution))
        else:
            out.append(Track(position_code(body), position_code(primary), body, series, 0.0, "the solution"))
    return out


def scaled(series, factor):
    return Segments(series.origin_d, series.length_d, series.first, factor * series.coefficients)


def barycentre_track(solution):
    """The Earth-Moon barycentre (3) about the solar-system barycentre (0) over the solution's span, refitted on
    its RECORDS from the ephemeris the solution's run read (``provenance["ephemeris"]``)."""
    from ..base.errors import InputError
    from ..orbits.sources import ephemeris_identity, orbit_source

    read = solution.provenance.get("ephemeris")
    name = read.get("name") if isinstance(read, dict) else read
    now = (ephemeris_identity(name) or {}).get("sha256")
    if isinstance(read, dict) and read.get("sha256") and now != read["sha256"]:
        raise InputError("ephemeris", name, f"the file the solution's run read (sha256 {read['sha256'][:16]}...): "
                                            "it has changed since")
    lo, hi = solution.span
    source = orbit_source(name)
    if source.jpl_kernel:
        reader = source.open(lo, hi)

        def positions(t):
            return reader.relative_states(EMB, "solar_system_barycenter", t)[0]
    else:
        orbits = source.barycentric((EMB,), lo - 1.0, hi + 1.0)

        def positions(t):
            return np.asarray(orbits.positions(t))[:, 0]
    length, degree = RECORDS[EMB]
    segments, error = refitted(positions, (lo, hi), record_count(solution.segments, length), degree)
    return Track(position_code(EMB), 0, EMB, segments, error, f"the ephemeris {name}")


def record_count(own, length_d):
    """The fewest records tiling the span of ``own`` (the solution's segments), each a whole number of its
    segments and at most ``length_d`` long (or one segment): the records' ends are the solution's segment ends,
    exact doubles in days and in seconds where those are (SPICE, in seconds, and the series, in days, then place
    a date alike in its record: an end one ulp off at 1e9 s moves Mars by 4 mm)."""
    count = len(own.coefficients)
    joined = [m for m in range(1, count + 1) if count % m == 0 and m * own.length_d <= length_d * (1 + 1e-12)]
    return count // max(joined, default=1)


def refitted(positions, span, count, degree):
    """(``count`` Segments of ``degree`` tiling ``span`` (TDB days) exactly, fitted to ``positions`` (t -> (n, 3)
    km) at their Chebyshev points; the largest distance, km, between them and ``positions`` at the extrema of
    T_(n+1))."""
    lo, hi = span
    empty = Segments(lo, (hi - lo) / count, 0, np.zeros((count, 3, degree + 1)))
    nodes, checks = empty.nodes(0, count)
    values = np.asarray(positions(nodes.ravel())).reshape(count, degree + 1, 3)
    segments = Segments(lo, (hi - lo) / count, 0,
                        interpolating_at(values.transpose(0, 2, 1), empty.normalised(nodes, 0)))
    fitted = segments.at_normalised(empty.normalised(checks, 0)).reshape(-1, 3)
    truth = np.asarray(positions(np.clip(checks.ravel(), lo, hi)))
    return segments, float(np.linalg.norm(fitted - truth, axis=1).max())
