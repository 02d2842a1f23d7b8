"""What a scene's run returns: a RunResult (table, summary, figures) and the attitude table.

Edge module (imports astropy), below ``scenes``: scenes build their result here, and
``runner.run_scenario`` completes its summary.
"""
from dataclasses import dataclass, field
from typing import Callable

from .schema import tdb_days_to_time


@dataclass
class RunResult:
    """``scenario``: the Scenario run; ``table``: QTable (``time`` column TDB + unit-carrying columns);
    ``summary``: JSON-ready dict whose metric keys carry their unit in the name;
    ``figures``: name -> function(matplotlib Figure) drawing one plot; ``states``: the main run's states at
    the outputs (integrators.base.Trajectory; evaluated from ``solution`` where there is one); ``solution``: the
    main run as a continuous Solution (spinorbit.solutions) for a scene kept as one, the one integration the
    table was evaluated from, else None with ``solution_absent`` saying why."""

    scenario: object
    table: object
    summary: dict
    figures: dict[str, Callable] = field(default_factory=dict)
    states: object = None
    solution: object = None
    solution_absent: str | None = None


def attitude_table(solution):
    """QTable with TDB time, quaternion (body -> inertial) and body angular velocity (rad/d)."""
    import astropy.units as units
    from astropy.table import QTable

    table = QTable()
    table["time"] = tdb_days_to_time(solution.t)
    for i, name in enumerate("wxyz"):
        table[f"q_{name}"] = solution.quaternion[:, i]
    for i, name in enumerate("xyz"):
        table[f"omega_{name}"] = solution.omega[:, i] * units.rad / units.d
    return table
