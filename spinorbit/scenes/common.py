"""Pieces every scene module shares: run the integrator, build the table, draw plots (spinorbit.plots)."""
import numpy as np

from ..bodies import RigidBody
from ..errors import PhysicsError, ScenarioError
from ..plots import plot_series  # scenes call common.plot_series
from ..run_result import RunResult, attitude_table  # noqa: F401  (scenes call common.attitude_table)
from ..simulate import simulate


def u():
    """astropy.units, imported on first use."""
    import astropy.units as units

    return units


def rigid_body(scenario, key="body.moments"):
    """RigidBody from principal moments at ``key``; a non-physical body is a ScenarioError on that key."""
    moments = scenario[key]
    try:
        return RigidBody.from_principal(*moments, name=key)
    except PhysicsError as exc:
        raise ScenarioError(key, moments.tolist(), f"a rigid body ({exc})") from None


def simulate_scenario(scenario, system, t_out, part=None):
    """simulate() with the scenario's [integrator] table: the scene's main run checkpointed (when the command
    line gives a checkpoint), a further run ``part`` in a checkpoint of its own."""
    checkpoint = scenario.checkpoint
    if checkpoint is not None and part is not None:
        checkpoint = checkpoint.part(part)
    label = scenario.name if part is None else f"{scenario.name} ({part})"
    return simulate(system, t_out, scenario["integrator.method"], scenario.integrator_options(),
                    scenario["integrator.estimate_error"], checkpoint, label)


def result(scenario, table, summary, figures, solution):
    return RunResult(scenario, table, summary, figures, solution)


def decimal_year(t):
    """TDB days from J2000 -> Julian epoch (decimal year), for time axes."""
    return 2000.0 + np.asarray(t) / 365.25


def plot_omega(solution):
    return plot_series(solution.t - solution.t[0], solution.omega.T, "days from start",
                       "body angular velocity [rad/d]", ["x", "y", "z"])
