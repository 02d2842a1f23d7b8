"""The scenes whose integration is kept as a solution: where each starts, how it builds its System for a
stretch of time, and the grid of its Chebyshev segments.

A stored solution starts once, at its anchor (the state the scene starts from there), and is extended from its
ends: each later stretch is the same model started at the state where the last run stopped.  The grids keep
the fit's error below the integration's (measured: tests/test_solutions.py, benchmarks/bench_solutions.py).
"""
from dataclasses import dataclass

import numpy as np

from .chebyshev import Grid

J2000_ISO = "2000-01-01T12:00:00"
DE421_EPOCH_ISO = "1969-06-28T00:00:00"      # DE421's JDEPOC, 2440400.5 TDB: where its initial conditions hold


@dataclass(frozen=True)
class Kind:
    """A scene kind kept as a solution: its grid, the ISO TDB epoch its first run starts from (None: the
    scene's own span.start), and whether its solution holds what SPICE kernels carry (an attitude or
    integrated positions: ``spinorbit export``)."""

    name: str
    grid: Grid
    anchor: str | None
    kernels: bool = True
    attitude: str | None = None       # a gyroscopic body whose attitude layer it answers with (attitude_layer)


KINDS = {"moon_libration": Kind("moon_libration", Grid(0.0, 4.0, 13), J2000_ISO),
         "earth_precession_nutation": Kind("earth_precession_nutation", Grid(0.0, 8.0, 14), None, kernels=False),
         "earth_moon_coupled": Kind("earth_moon_coupled", Grid(0.0, 4.0, 13), J2000_ISO),
         "solar_system": Kind("solar_system", Grid(0.0, 4.0, 13), DE421_EPOCH_ISO),
         "mars_orientation": Kind("mars_orientation", Grid(0.0, 8.0, 14), J2000_ISO, attitude="mars")}


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


def own_start(scenario):
    """Where ``scenario`` asks its model to start when a key says so (TDB days), or None (the kind's anchor, the
    stored solution's): the Moon's ``model.start``; the solar system's span.start with ``start.epoch = "span"``."""
    if scenario.kind == "moon_libration" and scenario.params.model.start is not None:
        from ..starts.moon import start_epoch

        return start_epoch(scenario.params)
    if scenario.kind == "solar_system" and scenario.params.start.epoch == "span":
        return float(scenario.params.span.start)
    if scenario.kind == "mars_orientation":
        from ..starts.mars import start_epoch
        return start_epoch(scenario.params)
    return None


def first_start(scenario):
    """(t0, state) where the kind's first run starts: the scene's start at the anchor (the Earth: at its own
    span.start, with the start its own span gives it; the solar system: at DE421's epoch, where the scene starts
    by default, from DE421's initial conditions, or with ``start.epoch = "span"`` from DE421's states there)."""
    from ..schema import parse_tdb_days

    anchor = KINDS[scenario.kind].anchor
    if anchor is None:
        built = system(scenario, None)
    else:
        t0 = float(parse_tdb_days("anchor", anchor))
        built = system(stretch(scenario, t0, t0 + 4.0, t0), None)
    return float(built.t0), built.y0.copy()


def ephemeris(scenario, built, lo, hi):
    """The JPL ephemeris reader of ``scenario``'s orbit source over [lo, hi] TDB days where ``built`` (its System)
    sees a body from another (fit.seen: that position is fitted from it, fit.components), or None (nothing seen,
    or a source that is not a JPL kernel)."""
    from .fit import seen

    if not seen(built):
        return None
    source = scenario.params.orbit.source
    return source.open(lo, hi) if source.jpl_kernel else None


def system(scenario, start):
    """The scene's System over the scenario's span, started at ``start`` = (t0, state) (its Scene's
    ``restart``), or at the scene's own start (``start`` None: its ``build``)."""
    scene, p = scenario.scene, scenario.params
    if start is None:
        return scene.build(p, scenario.output_times()).system
    return scene.restart(p, start)
