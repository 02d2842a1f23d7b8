"""The scenes whose integration is kept as a solution: where each starts, how it builds its System for a
stretch of time, and the grid of its Chebyshev segments.

A stored solution starts once, at its anchor (the state the scene starts from there), and is extended from its
ends: each later stretch is the same model started at the state where the last run stopped.  The grids keep
the fit's error below the integration's (measured: tests/test_solutions.py, benchmarks/bench_solutions.py).
"""
from dataclasses import dataclass

import numpy as np

from .chebyshev import grid_indices
from .fit import Grid

J2000_ISO = "2000-01-01T12:00:00"


@dataclass(frozen=True)
class Kind:
    """A scene kind kept as a solution: its grid, and the ISO TDB epoch its first run starts from (None: the
    scene's own span.start)."""

    name: str
    grid: Grid
    anchor: str | None

    def grid_bounds(self, lo, hi):
        """[lo, hi] rounded out to the grid's segment ends."""
        first, count = grid_indices(self.grid.origin_d, self.grid.length_d, lo, hi)
        return (self.grid.origin_d + first * self.grid.length_d,
                self.grid.origin_d + (first + count) * self.grid.length_d)


KINDS = {"moon_libration": Kind("moon_libration", Grid(0.0, 4.0, 13), J2000_ISO),
         "earth_precession_nutation": Kind("earth_precession_nutation", Grid(0.0, 8.0, 14), None),
         "earth_moon_coupled": Kind("earth_moon_coupled", Grid(0.0, 4.0, 13), J2000_ISO)}


def iso(t):
    from ..schema import tdb_days_to_time

    return tdb_days_to_time(np.atleast_1d(t)).isot


def stretch(scenario, lo, hi, t0):
    """``scenario`` over [lo, hi] TDB days started at t0 (the Moon's orbits are sampled from its start)."""
    import copy

    from ..scenarios import Scenario, set_value

    start, end = iso([lo, hi])
    values = {"span.start": start, "span.end": end}
    if scenario.kind == "moon_libration":
        values["model.start"] = iso(t0)[0]
    data = copy.deepcopy(scenario.data)
    for key, value in values.items():
        set_value(data, key, value)
    return Scenario(data, scenario.path)


def first_start(scenario):
    """(t0, state) where the kind's first run starts: the scene's start at the anchor (the Earth: at its own
    span.start, with the start its own span gives it)."""
    from ..schema import parse_tdb_days

    anchor = KINDS[scenario.kind].anchor
    if anchor is None:
        built = system(scenario, None)
    else:
        t0 = float(parse_tdb_days("anchor", anchor))
        built = system(stretch(scenario, t0, t0 + 4.0, t0), None)
    return float(built.t0), built.y0.copy()


def system(scenario, start):
    """The scene's System over the scenario's span, started at ``start`` = (t0, state), or at the scene's own
    start (``start`` None)."""
    build = {"moon_libration": _moon, "earth_precession_nutation": _earth,
             "earth_moon_coupled": _earth_moon}[scenario.kind]
    return build(scenario, start)


def _moon(scenario, start):
    from ..scenes.moon_libration.model import build_system

    if start is None:
        return build_system(scenario, scenario["orbit.source"])[0]
    return _moon_from(scenario, start)


def _moon_from(scenario, start):
    """The Moon scene's System (its model.build_system) started at a stored state: the same model on orbits
    sampled over the stretch, without the DE421 start (its core carried from DE421's epoch) it would replace."""
    from ..models.assemblies.moon import LEVELS, moon
    from ..orbits.sources import sample_orbits
    from ..references.moon_de421 import earth_pole
    from ..scenes.moon_libration.model import MARGIN_D

    level, extra = LEVELS[scenario["model.level"]], tuple(scenario["model.terms"])
    first = min(start[0], *scenario.bounds) - MARGIN_D
    last = max(start[0], *scenario.bounds) + MARGIN_D
    orbits = sample_orbits(scenario["orbit.source"], "moon", level.bodies, first, last, scenario["orbit.step"])
    pole = earth_pole(first, last) if "earth_j2" in level.terms + extra else None
    built = moon(scenario["model.level"], orbits, extra, scenario["model.tides"], pole, float(start[0]))
    built.meta["source"] = scenario["orbit.source"]
    return built.with_start(*start)


def _earth(scenario, start):
    from ..scenes.earth_precession_nutation import start as earth_start

    if start is None:
        return earth_start.build(scenario, scenario.output_times())[0]
    earth_start.check(scenario)
    built = earth_start.earth_system(scenario, earth_start.orbits(scenario), scenario["earth.model"],
                                     float(start[0]))
    return built.with_start(*start)


def _earth_moon(scenario, start):
    from ..models.assemblies.earth_moon import SWITCHES, solar_system
    from ..scenes import earth_moon_coupled as scene

    switches = tuple(name for name in SWITCHES if scenario[f"model.{name}"])
    external, _ = scene.external_bodies(scenario)
    if start is None:
        return scene.system(scenario, external, switches)
    return solar_system(external, switches, float(start[0])).with_start(*start)
