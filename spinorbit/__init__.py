"""spinorbit: orbit-spin coupling after Euler, *Theoria motus corporum solidorum* ch. 15-16.

Notebook entry points::

    import spinorbit
    scene = spinorbit.load_scenario("scenarios/free_body.toml", ["span.end=100 d"])
    result = spinorbit.run_scenario(scene)
    result.table, result.summary

Internal units: TDB days from J2000.0, km, rad (see spinorbit.constants).
"""
__version__ = "0.1.0"


def load_scenario(path, overrides=()):
    """Read and validate a scenario TOML file (see spinorbit.scenarios)."""
    from .scenarios import load_scenario as _load

    return _load(path, overrides)


def run_scenario(scenario, overrides=()):
    """Run a scenario (path or Scenario) and return a RunResult with .table and .summary."""
    from .results import run_scenario as _run

    return _run(scenario, overrides)
