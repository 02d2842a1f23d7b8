"""The result of a run: an astropy QTable with a TDB time column, a summary, figures.

Edge module (imports astropy).  ``run_scenario`` is the one entry point used by
the command line and by notebooks.
"""
import math
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from .errors import IntegrationError
from .scenarios import Scenario, load_scenario


@dataclass
class RunResult:
    """``table``: QTable (``time`` column TDB + unit-carrying columns);
    ``summary``: JSON-ready dict whose metric keys carry their unit in the name;
    ``figures``: name -> function(matplotlib Figure) drawing one plot."""

    scenario: Scenario
    table: object
    summary: dict
    figures: dict[str, Callable] = field(default_factory=dict)
    solution: object = None


def run_scenario(scenario, overrides=()):
    """Run a scenario (a Scenario or a path to its TOML file) and return a RunResult."""
    if not isinstance(scenario, Scenario):
        scenario = load_scenario(scenario, overrides)
    try:
        with np.errstate(divide="ignore", invalid="ignore", over="ignore"):   # NaN/inf are reported as not measured
            result = scenario.module.run(scenario)
    except IntegrationError as exc:
        if getattr(exc, "result", None) is None and getattr(exc, "partial", None) is not None:
            exc.result = partial_result(scenario, exc)
        raise
    result.summary = mark_unmeasured({**base_summary(scenario), **result.summary})
    return result


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
    from .scenes.common import attitude_table

    partial = exc.partial
    run = {"method": partial.method, "wall_s": partial.wall_s, "rhs_evaluations": partial.nfev,
           "steps": partial.nsteps, "failed_at_tdb_d": exc.t, "outputs_written": int(partial.t.size)}
    table = attitude_table(partial) if partial.t.size else None
    return RunResult(scenario, table, mark_unmeasured({**base_summary(scenario), "run": run}), {}, partial)


def base_summary(scenario):
    return {
        "scene": scenario.name,
        "kind": scenario.kind,
        "title": scenario["scene.title"],
        "span": {"start_tdb": scenario["span.start"], "end": scenario["span.end"],
                 "step_d": scenario["span.step"]},
        "integrator": {"method": scenario["integrator.method"], **scenario.integrator_options()},
    }
