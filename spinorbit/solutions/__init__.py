"""Integrations kept as continuous solutions: fitted (fit, chebyshev), stored and extended (store), evaluated
(solution), exported as SPICE kernels (spice).

``solve(scene, sets, t_start, t_end)`` is the one entry: the stored solution of a built-in scene's model
(``sets``: its ``--set`` assignments) covering [t_start, t_end] TDB days, integrated only where the store
lacks it.
"""
from . import models, store
from .fit import integrate
from .solution import Solution, joined

__all__ = ["Solution", "solve", "for_scenario"]


def solve(scene, sets, t_start, t_end):
    """The Solution of built-in scene ``scene`` (a kind of models.KINDS) with ``sets`` over [t_start, t_end]."""
    return for_scenario(scenario_of(scene, sets), t_start, t_end)


def scenario_of(scene, sets):
    from ..scenarios import load_scenario

    return load_scenario(scene, list(sets))


def piece_scenario(scene, sets, lo, hi, t0):
    """The scenario of a stretch [lo, hi] TDB days of ``scene`` with ``sets``, started at t0."""
    return models.stretch(scenario_of(scene, sets), lo, hi, t0)


def for_scenario(scenario, t_start=None, t_end=None):
    """The Solution of ``scenario``'s model over [t_start, t_end] (default: its span); InputError for a
    scene kind that is not kept as a solution."""
    from ..errors import InputError

    if scenario.kind not in models.KINDS:
        raise InputError("scene", scenario.kind, f"a scene kept as a solution: {sorted(models.KINDS)}")
    lo, hi = scenario.bounds if t_start is None else (min(t_start, t_end), max(t_start, t_end))
    def extend(solution, a, b):
        from ..scenarios import scenario_errors

        with scenario_errors(scenario):         # a library InputError on the scenario key that set it
            return _extended(scenario, solution, a, b)

    return store.solve(store.record(scenario), lo, hi, extend)


def _extended(scenario, solution, lo, hi):
    """``solution`` (or a new one from the scene's start) extended to cover [lo, hi]: each stretch from the
    state where the last run stopped."""
    kind = models.KINDS[scenario.kind]
    if solution is None:
        t0, y0 = models.first_start(scenario)
        lo, hi = min(lo, t0), max(hi, t0)
        return _piece(scenario, kind, (t0, y0), lo, hi)
    if lo < solution.span[0]:
        solution = joined(solution, _piece(scenario, kind, solution.ends["start"], lo, solution.span[0]))
    if hi > solution.span[1]:
        solution = joined(solution, _piece(scenario, kind, solution.ends["end"], solution.span[1], hi))
    return solution


def _piece(scenario, kind, start, lo, hi):
    """A Solution over [lo, hi] (rounded out to the grid) of the scene's System started at ``start``."""
    lo, hi = kind.grid_bounds(lo, hi)
    stretch = models.stretch(scenario, lo, hi, start[0])
    system = models.system(stretch, start)
    method, options = stretch["integrator.method"], stretch.integrator_options()
    piece = integrate(system, kind.grid, lo, hi, method, options, label=f"{scenario.kind} solution")
    run = {"span_tdb_d": [lo, hi], "start_tdb_d": float(start[0]),
           **{k: v for k, v in piece.run.items() if isinstance(v, (int, float, str, type(None)))}}
    provenance = {"scene": scenario.kind, "scenario": str(scenario.path),
                  "keys": store.record(scenario)["keys"], "ephemeris": scenario.get("orbit.source"),
                  "integrator": {"method": method, **options}, "code_version": store.code_version(),
                  "grid": {"segment_d": kind.grid.length_d, "degree": kind.grid.degree},
                  "state_size": int(system.layout.size), "fit_error": piece.fit_error,
                  "fit_error_how": "the series against the integrator's output at the Chebyshev points of the "
                                   "second kind (between the fitted points, and the segments' ends)",
                  "runs": [run]}
    return Solution(piece.segments, piece.layout, provenance, piece.ends)


def integration_error(solution):
    """{integration_error_*: max over the runs} of a solution's provenance."""
    out = {}
    for run in solution.provenance.get("runs", []):
        for k, v in run.items():
            if k.startswith("integration_error_") and isinstance(v, float):
                out[k] = max(out.get(k, 0.0), v)
    return out
