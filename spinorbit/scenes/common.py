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


def simulate_scenario(scenario, system, t_out):
    """simulate() with the scenario's [integrator] table."""
    return simulate(system, t_out, scenario["integrator.method"], scenario.integrator_options(),
                    scenario["integrator.estimate_error"])


def fixed_step_run(scenario, rhs, params, y0, default_step, checkpoint, label):
    """(states at the output times, the run's point) of the compiled RK8 at ``integrator.step`` (days;
    ``default_step`` when unset) from (span.start, y0), checkpointed (spinorbit.checkpoint) and timed
    without the kernels' compilation."""
    import time

    from ..checkpoint import fixed_step

    step = float(scenario.integrator_options().get("step", default_step))
    t0, t = scenario.t_start, scenario.output_times()
    fixed_step(rhs, params, t0, y0, t[:2], step)                    # compile outside the timing
    started = time.perf_counter()
    states = fixed_step(rhs, params, t0, y0, t, step, checkpoint, label)
    wall = time.perf_counter() - started
    steps = int(np.ceil(abs(t[-1] - t0) / step - 1e-9))
    return states, {"method": "rk8", "step_d": step, "steps": steps, "rhs_evaluations": 12 * steps, "wall_s": wall}


def result(scenario, table, summary, figures, solution):
    return RunResult(scenario, table, summary, figures, solution)


def decimal_year(t):
    """TDB days from J2000 -> Julian epoch (decimal year), for time axes."""
    return 2000.0 + np.asarray(t) / 365.25


def plot_omega(solution):
    return plot_series(solution.t - solution.t[0], solution.omega.T, "days from start",
                       "body angular velocity [rad/d]", ["x", "y", "z"])
