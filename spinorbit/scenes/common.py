"""Pieces every scene module shares: run the integrator, build the table, draw plots."""
import numpy as np

from ..bodies import RigidBody
from ..errors import PhysicsError, ScenarioError
from ..run_result import RunResult, attitude_table  # noqa: F401  (scenes call common.attitude_table)
from ..schema import tdb_days_to_time
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


def result(scenario, table, summary, figures, solution):
    return RunResult(scenario, table, summary, figures, solution)


def plot_series(x, ys, xlabel, ylabel, labels=None, logy=False):
    """A drawing function for reports.write_plots: one or more curves against x."""
    ys = np.atleast_2d(ys)

    def draw(fig):
        ax = fig.add_subplot()
        for i, y in enumerate(ys):
            ax.plot(x, y, lw=0.8, label=None if labels is None else labels[i])
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        if logy:
            ax.set_yscale("log")
        if labels is not None:
            ax.legend()
        ax.grid(alpha=0.3)

    return draw


def plot_panels(x, panels, xlabel):
    """A drawing function: stacked panels sharing x; ``panels`` = [(ys, labels, ylabel), ...];
    the second curve of a panel is drawn dashed over the first (a reference overlaid)."""

    def draw(fig):
        axes = fig.subplots(len(panels), 1, sharex=True)
        for ax, (ys, labels, ylabel) in zip(np.atleast_1d(axes), panels):
            for i, (y, label) in enumerate(zip(np.atleast_2d(ys), labels)):
                ax.plot(x, y, lw=1.2 if i == 0 else 0.9, ls="-" if i == 0 else "--", label=label)
            ax.set_ylabel(ylabel)
            ax.legend(fontsize=8, loc="upper right")
            ax.grid(alpha=0.3)
        np.atleast_1d(axes)[-1].set_xlabel(xlabel)

    draw.figsize = (8, 1.0 + 2.2 * len(panels))          # read by reports.write_plots
    return draw


def titled(draw, title):
    """Give a drawing function the plot title reports.write_plots puts above it (with scene and span)."""
    draw.title = title
    return draw


def decimal_year(t):
    """TDB days from J2000 -> Julian epoch (decimal year), for time axes."""
    return 2000.0 + np.asarray(t) / 365.25


def plot_omega(solution):
    return plot_series(solution.t - solution.t[0], solution.omega.T, "days from start",
                       "body angular velocity [rad/d]", ["x", "y", "z"])
