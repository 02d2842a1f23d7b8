"""Running a scenario: ``run_scenario``, the one entry point of the command line, notebooks and the API, and
the one runner of every scene.

Edge module (imports astropy): loads the scenario, then for its scene (spinorbit.scene.declaration.Scene) builds
the model, integrates it once (a scene kept as a solution: into a continuous Solution, spinorbit.solutions, whose
states at the output times the scene compares), has the scene compare, makes the table, and completes the
:class:`~spinorbit.scene.run_result.RunResult` with the summary every run has (span, integrator, the solution, verdict,
provenance; NaN turned into "not measured").
"""
import functools
import math
import re
import sys
from dataclasses import replace

import numpy as np

from ..base.errors import IntegrationError, ScenarioError
from ..scene.declaration import Run, integrate, scenario_errors
from ..scene.run_result import RunResult, attitude_table
from ..solutions import build_scenario, for_run, keep
from .scenarios import Scenario, load_scenario


def run_scenario(scenario, overrides=()):
    """Run a scenario (a Scenario or a path to its TOML file) and return a RunResult."""
    if not isinstance(scenario, Scenario):
        scenario = load_scenario(scenario, overrides)
    elif overrides:
        raise ScenarioError("overrides", overrides, "none with a Scenario (they apply to a file: pass its path)")
    try:
        # NaN/inf are reported as not measured; the library's InputError names its scenario key
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"), scenario_errors(scenario):
            result = run_scene(scenario)
    except IntegrationError as exc:
        if getattr(exc, "result", None) is None and getattr(exc, "partial", None) is not None:
            exc.result = partial_result(scenario, exc)
        raise
    from ..scene.verdict import evaluate
    from .provenance import provenance

    summary = mark_unmeasured({**base_summary(scenario), **result.summary, "status": "ok"})
    resumed = getattr(scenario.checkpoint, "resumed_outputs", 0)
    if resumed:                          # run.wall_s is then this process's part only
        summary.setdefault("run", {})["resumed_after_outputs"] = resumed
    comparison = summary.get("comparison", {})
    spec = scenario.scene.verdict_for(scenario.params, comparison)
    summary["verdict"] = evaluate(spec, comparison, scenario.params.span.length, scenario.name,
                                  span_label(scenario), summary.get("not_measured"))
    summary["provenance"] = provenance(scenario)
    result.summary = summary
    if result.table is not None:
        from ..scene.columns import describe

        describe(result.table)
        result.table.meta.update({"scene": scenario.name, "title": summary["title"], **summary["provenance"]})
    return result


def run_scene(scenario):
    """The scene's run: build its model once, integrate it (:func:`main_run`), let the scene compare the states
    at the output times, make the table (the attitude table and the scene's columns, or the scene's own) and the
    summary."""
    scene, p = scenario.scene, scenario.params
    times = scenario.output_times()
    model = scene.build(build_scenario(scenario).params, times)     # a stored kind's: over its grid's span
    run = Run(p, model, times, functools.partial(integrate, scenario))
    solution, section = None, {"kept": False, "why": "the scene has no main run (nothing of its own integrated)"}
    if model.system is not None:
        run.fitted, run.solution, run.point, section = main_run(scenario, model.system, times)
        solution = run.fitted
    outcome = scene.compare(p, run)
    table = outcome.table
    if table is None and run.solution is not None and run.solution.layout.quaternions:
        table = attitude_table(run.solution)
        for name, column in outcome.columns.items():
            table[name] = column
    if solution is not None:                     # the run is whole: its solution offered to the store
        section.update(stored(scenario, solution))
    summary = {"comparison": outcome.comparison, "run": run.point, "solution": section, **outcome.sections}
    if outcome.not_measured:
        summary["not_measured"] = {**summary.get("not_measured", {}), **outcome.not_measured}
    return RunResult(scenario, table, summary, outcome.figures, run.solution, solution,
                     None if solution is not None else section["why"])


def main_run(scenario, system, times):
    """(Solution or None, states at the output times, the run's point, summary["solution"]): a scene kept as a
    solution integrated once into a Solution (solutions.for_run: its fit's error within the run's own) and kept
    in the store where it is the stored model (solutions.keep), its states at the outputs evaluated from it;
    any other run integrated to the outputs (checkpointed as the scenario says), the reason in the section.  A
    fitted run that fails is run again to the outputs: its partial result (IntegrationError.partial) holds the
    states at the output times up to the failure, as any run's does."""
    try:
        solution, why = for_run(scenario, system)
    except IntegrationError as exc:
        solution, why = None, f"the run to the Chebyshev points failed ({exc})"
    if solution is None:
        states, point = integrate(scenario, system, times)
        return None, states, point, {"kept": False, "why": why}
    run = solution.provenance["runs"][0]
    point = {k: v for k, v in run.items() if k not in ("span_tdb_d", "start_tdb_d")}
    section = {"kept": True, "span_tdb_d": list(solution.span), "segments": len(solution.segments.coefficients),
               "segment_d": solution.segments.length_d, "degree": solution.segments.degree,
               **solution.fit_error, **{k: v for k, v in point.items() if k.startswith("integration_error_")}}
    states = replace(solution.states(times), nfev=run.get("rhs_evaluations", 0), nsteps=run.get("steps"),
                     wall_s=run.get("wall_s", 0.0))
    return solution, states, point, section


def stored(scenario, solution):
    """{"stored": path or None, "not_stored_because": why} of a finished run's Solution offered to the store
    (solutions.keep): not waiting on another process's lock beyond store.OFFER_WAIT_S, nor failing the run on a
    store it cannot write (both said in one line)."""
    from ..base.verified import Busy

    try:
        path, why = keep(scenario, solution)
    except (Busy, OSError) as exc:               # the run's result stands without the store
        why = str(exc) if isinstance(exc, Busy) else f"{type(exc).__name__}: {exc.strerror or exc}"
        print(f"spinorbit: the run's solution was not stored ({why})", file=sys.stderr)
        return {"stored": None, "not_stored_because": why}
    return {"stored": str(path)} if path else {"stored": None, "not_stored_because": why}


def mark_unmeasured(summary):
    """Replace every non-finite number in ``summary`` by None, with its reason in ``summary["not_measured"]``.

    A scene that knows why a value cannot be measured sets it to None and gives the
    reason itself (``not_measured[dotted key] = reason``); any NaN or inf left is
    caught here, so summary.json is always valid JSON and never holds NaN.
    """
    reasons = dict(summary.get("not_measured", {}))

    def clean(value, name):
        if hasattr(value, "tolist"):              # numpy arrays and scalars
            value = value.tolist()
        if isinstance(value, dict):
            return {k: clean(v, f"{name}.{k}" if name else str(k)) for k, v in value.items()}
        if isinstance(value, (list, tuple)):
            return [clean(v, name) for v in value]
        if isinstance(value, float) and not math.isfinite(value):
            reasons.setdefault(name, f"the computed value was {value} (not a measurement)")
            return None
        return value

    cleaned = clean({k: v for k, v in summary.items() if k != "not_measured"}, "")
    return {**cleaned, "not_measured": reasons} if reasons else cleaned


def partial_result(scenario, exc):
    """RunResult of the output an integrator produced before it failed (``exc.partial``, a Solution)."""
    partial = exc.partial
    run = {"method": partial.method, "wall_s": partial.wall_s, "rhs_evaluations": partial.nfev,
           "steps": partial.nsteps, "failed_at_tdb_d": exc.t, "outputs_written": int(partial.t.size)}
    table = attitude_table(partial) if partial.t.size else None
    from .provenance import provenance

    summary = {**base_summary(scenario), "run": run, "status": "failed", "provenance": provenance(scenario)}
    return RunResult(scenario, table, mark_unmeasured(summary), {}, partial,
                     solution_absent=f"the integration failed at {exc.t} TDB days")


def base_summary(scenario):
    p = scenario.params
    start, end = _tdb_text(p.span.start), _tdb_text(p.span.end)
    return {
        "scene": scenario.name,
        "kind": scenario.kind,
        "title": title_for_span(p.scene.title, scenario),
        "span": {"start_tdb": start, "end_tdb": end, "step_d": p.span.step, "years": span_label(scenario)},
        "integrator": {"method": p.integrator.method, **p.integrator.options()},
    }


def _tdb_text(t):
    """TDB days from J2000 as an ISO date (TDB), or, before the years ERFA dates (a deep-time span), as days."""
    from erfa import ErfaError

    from ..scene.schema import tdb_days_to_time

    try:
        return tdb_days_to_time(t).isot
    except (ErfaError, ValueError):
        return f"{t:.10g} d from J2000"


JULIAN_YEAR_D = 365.25


LONG_SPAN_YR = 10_000          # spans at least this long are labelled in kyr from J2000
GEOLOGICAL_SPAN_YR = 1e8       # and these in Gyr


def span_label(scenario):
    """The run's span for titles: calendar years "1900–2050" (Julian epochs), kyr or Gyr from J2000 for deep
    time, or its length in days."""
    length = scenario.params.span.length
    if length < JULIAN_YEAR_D:
        return f"{length:.4g} d"
    if length >= GEOLOGICAL_SPAN_YR * JULIAN_YEAR_D:   # the Earth-Moon history: Gyr
        g0, g1 = (t / JULIAN_YEAR_D / 1e9 for t in (scenario.params.span.start, scenario.params.span.end))
        return f"{g0:.4g} to {g1:.4g} Gyr from J2000".replace("-", "−")
    if length >= LONG_SPAN_YR * JULIAN_YEAR_D:         # deep time: kyr from J2000, as La2004 counts
        k0, k1 = (t / JULIAN_YEAR_D / 1000.0 for t in (scenario.params.span.start, scenario.params.span.end))
        return f"{k0:.0f} to {k1:.0f} kyr from J2000".replace("-", "−")
    y0, y1 = (2000.0 + t / JULIAN_YEAR_D for t in (scenario.params.span.start, scenario.params.span.end))
    digits = 0 if length >= 2 * JULIAN_YEAR_D else 1
    return f"{y0:.{digits}f}–{y1:.{digits}f}"


_YEAR_RANGE = re.compile(r"\b\d{4}\s*[-–]\s*\d{4}\b")
_DURATION = re.compile(r"\b\d+(\.\d+)? yr\b")


def title_for_span(title, scenario):
    """The scene title with its year range (or "10 yr") replaced by the span actually run."""
    if _YEAR_RANGE.search(title):
        return _YEAR_RANGE.sub(span_label(scenario), title, count=1)
    if _DURATION.search(title):
        return _DURATION.sub(f"{scenario.params.span.length / JULIAN_YEAR_D:.3g} yr", title, count=1)
    return title
