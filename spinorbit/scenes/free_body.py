"""Torque-free asymmetric rigid body against Euler's closed form (ch. 15 §808; Euler 1758 via Cayley).

Compares the integrated body angular velocity and attitude with the Jacobi
elliptic-function solution of spinorbit.theory.FreeRigidBody.
"""
import numpy as np

from ..constants import ARCSEC
from ..dynamics import invariant_drift, torque_free_system
from ..rotations import quat_from_euler313
from ..scenarios import Key
from ..simulate import attitude_difference_arcsec, simulate
from . import common

SCHEMA = {
    "body.moments": Key(unit="", size=3, help="principal moments A <= B <= C, any unit"),
    "body.omega0": Key(unit="rad/d", size=3, help="initial body angular velocity"),
    "body.attitude0": Key(unit="rad", size=3, default=np.zeros(3), help="initial JPL 3-1-3 angles"),
}


def run(scenario):
    body = common.rigid_body(scenario)
    from ..theory import FreeRigidBody

    omega0 = scenario["body.omega0"]
    q0 = quat_from_euler313(*scenario["body.attitude0"])
    system = torque_free_system(body.moments, q0, omega0, scenario.t_start)
    t = scenario.output_times()
    solution, point = common.simulate_scenario(scenario, system, t)

    exact = FreeRigidBody(body.moments, omega0, q0)
    dt = solution.t - scenario.t_start
    omega_exact = exact.omega(dt)
    q_exact = exact.attitude(dt)
    omega_err = np.abs(solution.omega - omega_exact).max() / np.linalg.norm(omega0)
    attitude_err = attitude_difference_arcsec(solution.quaternion, q_exact)
    comparison = {
        "regime": exact.regime,
        "period_d": exact.period,
        "omega_max_rel_error_vs_closed_form": float(omega_err),
        "attitude_max_error_vs_closed_form_arcsec": float(attitude_err.max()),
        "attitude_max_error_vs_closed_form_rad": float(attitude_err.max() * ARCSEC),
    }
    table = common.attitude_table(solution)
    table["attitude_error"] = attitude_err * common.u().arcsec
    figures = {
        "omega": common.plot_omega(solution),
        "error_vs_closed_form": common.plot_series(solution.t - scenario.t_start, attitude_err,
                                                   "days from start", "attitude error vs closed form [arcsec]"),
    }
    summary = {"comparison": comparison, "run": point, "invariants": invariant_drift(body.moments, solution.y)}
    return common.result(scenario, table, summary, figures, solution)
