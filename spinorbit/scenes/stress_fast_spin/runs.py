"""The fast spinner's run tables (``stress.runs``, ``stress.reference``): read, labelled, and the cheapest
run at each error level."""
from ...analysis.ladder import cheapest
from ...errors import ScenarioError
from ...integrators import METHODS, get_method


def options(run, key="stress.runs"):
    """(method, integrator options, span fraction) of one run table: the method's own option names."""
    method = run.get("method") if isinstance(run, dict) else None
    accepted = get_method(method).options if method in METHODS else {}
    if not accepted or set(run) - {"method", "span_fraction"} - set(accepted):
        raise ScenarioError(key, run, f"tables {{method = <one of {sorted(METHODS)}>, "
                                      f"<that method's options {sorted(accepted) or ''}, "
                                      "e.g. step = <days>>, span_fraction = <0-1>}")
    opts = {k: float(v) for k, v in run.items() if k in accepted}
    return method, opts, float(run.get("span_fraction", 1.0))


def label(method, opts):
    return f"{method} " + ", ".join(f"{k}={v:.3g}" for k, v in opts.items() if k != "atol")


def winner(rows, key, levels):
    """The cheapest full-span run at each error level (``key`` <= level), as text."""
    best = [(level, cheapest(rows, key, level)) for level in levels]
    return "; ".join(f"<= {level:.0e} rad: {r['run']} ({r['wall_s']:.3g} s)" for level, r in best if r) or \
        "no run below 1e-6 rad"
