"""Integrations kept as continuous solutions: fitted (fit, chebyshev), stored and extended (store), evaluated
(solution), exported as SPICE kernels (spice).

``for_scenario(scenario, t_start, t_end)`` is the one entry: the stored solution of a loaded scenario's model
covering [t_start, t_end] TDB days, integrated only where the store lacks it.
``for_run(scenario, system)`` is the runner's: a scene's main run integrated once into a Solution, kept in
the store where it is the stored model (``keep``).
"""
import math

import numpy as np

from . import store, stretches
from .chebyshev import Grid
from .solution import Solution, joined

__all__ = ["Solution", "solve", "for_scenario", "for_export", "for_run", "keep", "attitude"]

MICROARCSEC = 1e-6                  # arcsec
# What a fit may differ from the integrator by when the integration's own estimate is smaller (or, for
# attitudes and positions, not made): the 1 uas and 1 mm; a rate or any other slice relative to its
# size, 1 uas in radians.
FIT_FLOORS = {"arcsec": MICROARCSEC, "km": 1e-6, "rel": MICROARCSEC * np.pi / 180 / 3600}
REFINEMENTS = 2                     # halvings of the segments tried before a run is handed on discrete
# A run of a kind kept as a solution is always fitted: the Solution is what the run gives.  What it costs
# (benchmarks/bench_run_fit.py, benchmarks/RESULTS.md): rk8 between its steps pays DOP853's continuous extension,
# four more right-hand sides in each step (+33 % of the integration).


def for_scenario(scenario, t_start=None, t_end=None):
    """The Solution of ``scenario``'s model over [t_start, t_end] (default: its span); InputError for a
    scene kind that is not kept as a solution."""
    stretches.stored(scenario)
    lo, hi = scenario.params.span.bounds if t_start is None else (min(t_start, t_end), max(t_start, t_end))
    def extend(solution, a, b):
        from ..scene.declaration import scenario_errors

        with scenario_errors(scenario):         # a library InputError on the scenario key that set it
            return _extended(scenario, solution, a, b)

    return store.solve(store.record(scenario), lo, hi, extend)


def for_export(scenario):
    """The Solution of exactly ``scenario``'s model over the whole segments covering its span: the store's
    (extended where it lacks the span) when its model is the stored one, else (a key starts it elsewhere:
    Stored.own_start) the scenario's own run fitted (for_run: its segments tile the span)."""
    from ..base.errors import InputError

    anchor, start = stretches.stored(scenario).anchor, stretches.own_start(scenario)
    if start is None or abs(start - anchor) < 1e-9:
        return attitude(scenario, for_scenario(scenario)).window(*scenario.params.span.bounds)
    solution, why = for_run(scenario, stretches.system(scenario, None))
    if solution is None:
        raise InputError("scene", scenario.kind, f"a model whose run can be fitted: {why}")
    return attitude(scenario, solution)


def attitude(scenario, solution):
    """``solution`` itself, or where the scene's body (``Stored.attitude``) is gyroscopic its attitude layer: the
    figure axis and the prime meridian that SPICE kernels and the API carry (attitude_layer)."""
    body = stretches.stored(scenario).attitude
    if body is None or f"{body}.spin" not in solution.layout:     # none, or its attitude integrated (a full model)
        return solution
    from .attitude_layer import layer

    return layer(solution, scenario, body)


def _extended(scenario, solution, lo, hi):
    """``solution`` (or a new one from the scene's start) extended to cover [lo, hi]: each stretch from the
    state where the last run stopped."""
    grid = stretches.grid(stretches.stored(scenario))
    if solution is not None and grid_of(solution) != grid:     # the store keeps its scene's grid only
        solution = None
    if solution is None:
        t0, y0 = stretches.first_start(scenario)
        lo, hi = min(lo, t0), max(hi, t0)
        return _piece(scenario, grid, (t0, y0), lo, hi)
    if lo < solution.span[0]:
        solution = joined(solution, _piece(scenario, grid, solution.ends["start"], lo, solution.span[0]))
    if hi > solution.span[1]:
        solution = joined(solution, _piece(scenario, grid, solution.ends["end"], solution.span[1], hi))
    return solution


def _piece(scenario, grid, start, lo, hi):
    """A Solution over [lo, hi] (rounded out to the scene's ``grid``) of the scene's System started at
    ``start``."""
    lo, hi = grid.bounds(lo, hi)
    from .fit import integrate

    stretch = stretches.stretch(scenario, lo, hi, start[0])
    system = stretches.system(stretch, start)
    method, options = stretch.params.integrator.method, stretch.params.integrator.options()
    piece = integrate(system, grid, lo, hi, method, options, label=f"{scenario.kind} solution",
                      ephemeris=stretches.ephemeris(stretch, system, lo, hi))
    return made(scenario, system, grid, piece, (lo, hi), method, options)


def made(scenario, system, grid, piece, span, method, options):
    """The Solution of a fitted ``piece`` of ``system`` (``scenario``'s model) over ``span``, with its
    provenance."""
    run = {"span_tdb_d": [float(span[0]), float(span[1])], "start_tdb_d": float(system.t0),
           **{k: v for k, v in piece.run.items() if isinstance(v, (int, float, str, type(None)))}}
    rec = store.record(scenario)
    provenance = {"scene": scenario.kind, "scenario": str(scenario.path), "model_start_tdb_d": float(system.t0),
                  "keys": rec["keys"], "ephemeris": {"name": rec["keys"].get("orbit.source"),
                                                     **(rec["ephemeris_file"] or {})},
                  "integrator": {"method": method, **options}, "code_version": store.code_version(),
                  "grid": {"segment_d": grid.length_d, "degree": grid.degree},
                  "state_size": int(system.layout.size), "fit_error": piece.fit_error,
                  "fit_error_how": "the series against the integrator's output at the extrema of T_(n+1) "
                                   "(between the fitted points, the segments' ends included)",
                  "runs": [run]}
    return Solution(piece.segments, piece.layout, provenance, piece.ends)


def grid_of(solution):
    """The Grid a Solution's segments lie on."""
    s = solution.segments
    return Grid(s.origin_d, s.length_d, s.degree)


def stored_grid_span(scenario):
    """The span a main run is integrated over when it is the model the store keeps (``stored_model``), started at
    its scene's anchor and run forward: its own span rounded out to the end of the scene's last segment (the
    runner builds its System over it), so that the store keeps its scene's grid whatever the run's length; None
    for any other run (it tiles its own span: :func:`run_grid`, and is not stored)."""
    declared, span = scenario.scene.stored, scenario.params.span
    if declared is None or declared.anchor is None or span.end <= span.start or stored_model(scenario, span.start):
        return None
    lo, hi = stretches.grid(declared).bounds(span.start, span.end)
    return (lo, hi) if lo == scenario.params.span.start else None


def build_scenario(scenario):
    """The scenario a main run's System is built from: ``scenario`` over :func:`stored_grid_span` (started where it
    starts), or ``scenario`` itself."""
    span = stored_grid_span(scenario)
    return scenario if span is None else stretches.stretch(scenario, *span, scenario.params.span.start)


def fitted_grid(scenario, grid, system, lo, hi, halvings=0):
    """(Grid, span) a main run over [lo, hi] is fitted on: the scene's own ``grid`` over :func:`stored_grid_span`
    when there is one and its segments follow the run's spin (``spin_segment_d``); else :func:`run_grid`, tiling
    the span exactly."""
    span = stored_grid_span(scenario)
    if not halvings and span is not None and spin_segment_d(system, grid.degree) >= grid.length_d:
        return grid, span
    return run_grid(grid, system, lo, hi, halvings), (lo, hi)


def run_grid(grid, system, lo, hi, halvings=0):
    """The scene's ``grid`` made to tile the run's span [lo, hi] exactly, the first segment starting at lo (no
    orbit is read beyond the span), of its degree, its segments no longer than its own nor than
    :func:`spin_segment_d` (halved ``halvings`` times)."""
    length = min(grid.length_d, spin_segment_d(system, grid.degree)) / 2 ** halvings
    count = max(1, int(np.ceil((hi - lo) / length - 1e-9)))
    return Grid(lo, (hi - lo) / count, grid.degree)


def spin_segment_d(system, degree):
    """The longest segment (days) on which a series of ``degree`` follows an attitude turning at the System's
    fastest body rate at its start (``*.omega``, rad/d; inf with none) within FIT_FLOORS' 1 uas: a quaternion
    turns at half the rate, and a series of cos(w t / 2) on a segment L has coefficients 2 J_k(w L / 4), whose
    first one left out, ~ 2 (w L / 8)^(n + 1) / (n + 1)! (Abramowitz & Stegun 9.1.7, 9.1.44), is the
    interpolant's error at the extrema of T_(n+1) (it vanishes at the fitted points, T_(n+1)'s roots); the angle
    between two quaternions is twice their difference: 4 (w L / 8)^(n + 1) / (n + 1)! is held to the floor."""
    rates = [np.linalg.norm(system.y0[part.index]) for part in system.layout.slices if part.name.endswith(".omega")]
    if not rates or max(rates) <= 0.0:
        return np.inf
    x = (FIT_FLOORS["rel"] / 4 * math.factorial(degree + 1)) ** (1.0 / (degree + 1))
    return 8.0 * x / max(rates)


def for_run(scenario, system):
    """(Solution, None) of a scene's main run: ``system`` (the System its scene built for the run) integrated
    once over the span to the Chebyshev points of the segments tiling it (run_grid) with the scenario's
    [integrator] and its error estimate as the scenario says, the series fitted; the segments halved (at most
    REFINEMENTS times) while the fit differs from the integrator by more than the run's own error
    (``fit_beyond_run``).  (None, why) for a run not fitted (``not_fitted``), or a fit never within the run."""
    from .fit import integrate

    why = not_fitted(scenario, system)
    if why:
        return None, why
    stored_grid, (lo, hi) = stretches.grid(scenario.scene.stored), scenario.params.span.bounds
    method, options = scenario.params.integrator.method, scenario.params.integrator.options()
    worst = np.inf
    for halvings in range(REFINEMENTS + 1):
        grid, (a, b) = fitted_grid(scenario, stored_grid, system, lo, hi, halvings)
        piece = integrate(system, grid, a, b, method, options, label=scenario.name,
                          estimate_error=scenario.params.integrator.estimate_error,
                          ephemeris=stretches.ephemeris(scenario, system, a, b))
        beyond = fit_beyond_run(piece.fit_error, piece.run, rounding_km(piece))
        if not beyond:
            return made(scenario, system, grid, piece, (a, b), method, options), None
        previous, worst = worst, max(piece.fit_error[key] for key in beyond)
        if worst > previous / 2:            # shorter segments do not help: not the series' truncation
            break
    return None, (f"its fit on segments of {grid.length_d:.4g} d differs from the integrator by more than the "
                  f"run's own error: {'; '.join(f'{k} {piece.fit_error[k]:.3g} > {b:.3g}' for k, b in beyond.items())}")


def rounding_km(piece):
    """The rounding floor of a fit's positions (km): a series of degree n sums n + 1 terms, each rounded to the
    double precision of the largest position fitted (Higham, Accuracy and Stability of Numerical Algorithms,
    §3.1: (n + 1) u)."""
    coefficients = piece.segments.coefficients
    sizes = [np.abs(coefficients[:, part.index, 0]).max() for part in piece.layout.slices if part.name.endswith(".r")]
    return (piece.segments.degree + 1) * np.finfo(float).eps * max(sizes, default=0.0)


def fit_beyond_run(fit_error, run, rounding_km=0.0):
    """{fit error key: bound} of what of a fit's error (fit.errors) exceeds the run's own error estimate
    (simulate's point), or FIT_FLOORS where the estimate is smaller (positions: or ``rounding_km``, their rounding
    floor).  Judged: the state's slices and the figure axes derived from it.  Stated, not judged: a body's position
    read from the orbit source (``*_from_*``: data, not integrated), and, in a run whose error is not estimated, a
    slice relative to its size (a rate: the issue bounds attitudes and positions, which keep their floors; the
    series of a rate, checked where rk8's steps join, differs from the integrator by the dense output's own error
    there, which only the estimate could bound)."""
    out = {}
    for key, value in fit_error.items():
        name = key.removeprefix("fit_error_")
        if "_from_" in name:
            continue
        unit = name.rsplit("_", 1)[1]
        if unit == "arcsec":
            estimate = run.get("integration_error_attitude_arcsec")
        elif unit == "km":
            estimate = max(run.get("integration_error_position_km") or 0.0, rounding_km)
        else:
            slice_name = name.removesuffix("_rel")
            estimate = run.get("integration_error_omega_rel" if slice_name.endswith("_omega") else
                               f"integration_error_{slice_name}_rel")
            if estimate is None:
                continue
        bound = max(estimate or 0.0, FIT_FLOORS.get(unit, 0.0))
        if not value <= bound:
            out[key] = bound
    return out


def not_fitted(scenario, system):
    """Why a run of ``system`` (its scene's main System) is not fitted, or "": a scene kind not kept as a
    solution, or an attitude turning in the shortest segment tried through more radians than half its series'
    degree (a day resolved on 8-d segments; the run is then integrated to its outputs)."""
    if scenario.scene.stored is None:
        from ..scenes import stored_kinds

        return (f"scene kind {scenario.kind} is not kept as a solution (the kinds that are: "
                f"{', '.join(sorted(stored_kinds()))})")
    grid = stretches.grid(scenario.scene.stored)
    finest = grid.length_d / 2 ** REFINEMENTS
    for part in system.layout.slices:
        if part.name.endswith(".omega") and system.y0 is not None:
            turn = float(np.linalg.norm(system.y0[part.index])) * finest
            if turn > grid.degree / 2:
                return (f"{part.name.split('.')[0]} turns {turn:.3g} rad in a {finest:g}-d segment (the grid's "
                        f"halved {REFINEMENTS} times), more than a series of degree {grid.degree} follows to 1 uas")
    return ""


def stored_model(scenario, t0):
    """Why a run of ``scenario`` started at t0 (TDB days) is not the model the store keeps for its record, or
    "": the store's starts at the scene's anchor (the Earth's record holds its span, so its start), its error
    estimated."""
    from ..base.errors import tdb_dates

    anchor = stretches.stored(scenario).anchor
    if not scenario.params.integrator.estimate_error:
        return "its integration error is not estimated (integrator.estimate_error = false)"
    if anchor is not None and abs(t0 - anchor) > 1e-9:
        return (f"it starts at {tdb_dates((t0,), 'seconds')} TDB, the stored one at "
                f"{tdb_dates((anchor,), 'seconds')} TDB")
    return ""


def keep(scenario, solution):
    """Put a run's Solution in the store where it is the stored model (``stored_model``) on its scene's grid,
    unless the store already holds a longer span of it.  (path, None), or (None, why not)."""
    why = stored_model(scenario, solution.provenance["runs"][0]["start_tdb_d"])
    grid = stretches.grid(stretches.stored(scenario))
    if not why and grid_of(solution) != grid:
        s = solution.segments
        why = (f"its segments ({s.length_d:.4g} d from {s.origin_d:.6g}, degree {s.degree}) are not the stored "
               f"grid's ({grid.length_d:g} d from {grid.origin_d:g}, degree {grid.degree})")
    if why:
        return None, why
    return store.offer(solution, store.record(scenario)), None


def integration_error(solution):
    """{integration_error_*: max over the runs} of a solution's provenance."""
    out = {}
    for run in solution.provenance.get("runs", []):
        for k, v in run.items():
            if k.startswith("integration_error_") and isinstance(v, float):
                out[k] = max(out.get(k, 0.0), v)
    return out
