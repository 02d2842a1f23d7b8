"""The Moon scene's System: the lunar model at the scenario's level, driven by its orbit source, started from
DE421's state (orientation, rates, core) at span.start -- or, for a span DE421's lunar series does not reach
(another ephemeris, e.g. DE440's 1550-2650), at the nearest epoch it does, integrated out from there."""
import numpy as np

from ..base.errors import InputError, ScenarioError
from ..models.assemblies.moon import LEVELS, TERMS

MARGIN_D = 1.0          # orbit samples beyond the outputs: the tide looks back tau (0.1 d)


def start_epoch(p):
    """model.start (default span.start), or the nearest epoch of DE421's lunar series (TDB days) when it lies
    outside."""
    from ..bodies.de421_orientation import span

    first, last = span()
    wanted = p.span.start if p.model.start is None else p.model.start
    return float(np.clip(wanted, first + MARGIN_D, last - MARGIN_D))


def build_system(p, source):
    """(System of the lunar model at the scenario's level, its terms + ``model.terms``, driven by ``source`` (an
    OrbitSource); the orbits); ``p`` the scene's parameters."""
    from ..models.assemblies.moon import moon
    from ..models.start import moon_de421
    from ..references.moon_de421 import earth_pole

    level, extra = LEVELS[p.model.level], p.model.terms
    if not isinstance(extra, list) or any(not isinstance(n, str) or n not in TERMS or n in level.terms
                                          for n in extra):
        raise ScenarioError("model.terms", extra, f"a list of terms not in the level's {list(level.terms)}, "
                                                  f"from {sorted(TERMS)}")
    t0 = start_epoch(p)
    first, last = min(t0, *p.span.bounds) - MARGIN_D, max(t0, *p.span.bounds) + MARGIN_D
    orbits = source.relative("moon", level.bodies, first, last, p.orbit.step)
    pole = earth_pole(first, last) if "earth_j2" in level.terms + tuple(extra) else None
    try:
        system = moon(p.model.level, orbits, tuple(extra), p.model.tides, pole, t0,
                      moon_de421(t0, level.core))
    except InputError as exc:
        if exc.name != "terms":
            raise
        raise ScenarioError("model.terms", extra, exc.accepted) from None
    system.meta["source"] = source.name
    return system, orbits


def difference_driven_by(p, run, other, mats):
    """(pole, longitude) differences, rad, of this run from the same run driven by the OrbitSource ``other``."""
    from ..analysis.librations import icrf_to_body, pole_and_longitude_difference

    try:
        system, _ = build_system(p, other)
    except InputError as exc:                      # the error is about this source, not orbit.source
        if exc.name != "source":
            raise
        raise ScenarioError("compare.source", other.name, exc.accepted) from None
    solution, _ = run.integrate(system, run.times, f"driven_by_{other.name}")
    return pole_and_longitude_difference(mats, icrf_to_body(solution.quaternion))


def started_at(p, start):
    """The lunar model of ``p`` started at a stored state ``start`` = (t0, y): the same model on orbits
    sampled over the stretch, without the DE421 start (its core carried from DE421's epoch) it replaces."""
    from ..models.assemblies.moon import moon
    from ..references.moon_de421 import earth_pole

    level, extra = LEVELS[p.model.level], tuple(p.model.terms)
    first, last = min(start[0], *p.span.bounds) - MARGIN_D, max(start[0], *p.span.bounds) + MARGIN_D
    orbits = p.orbit.source.relative("moon", level.bodies, first, last, p.orbit.step)
    pole = earth_pole(first, last) if "earth_j2" in level.terms + extra else None
    built = moon(p.model.level, orbits, extra, p.model.tides, pole, float(start[0]))
    built.meta["source"] = p.orbit.source.name
    return built.with_start(*start)
