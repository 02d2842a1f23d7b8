"""Torque-free asymmetric rigid body against Euler's closed form (ch. 15 §808; Euler 1758 via Cayley).

Compares the integrated body angular velocity and attitude with the Jacobi
elliptic-function solution of spinorbit.theory.FreeRigidBody.  Euler's
equations need only 0 < A <= B <= C; the triangle inequality A + B >= C of a
real mass distribution is not required here, so that the classic
Hairer-Lubich-Wanner test case (moments 2/3, 1, 2) can be run as published.
"""
import numpy as np

from ...analysis.invariants import invariant_drift
from ...constants import ARCSEC
from ...errors import PhysicsError, ScenarioError
from ...models.assemblies.idealised import free_body
from ...rotations import quat_angle, quat_from_euler313
from ...schema import ANGLE, SPIN, Key
from ...verdict import Check, Verdict
from .. import common

TAYLOR = True          # every term a function of the state and the time: heyoka's Taylor integrator takes it
SCHEMA = {
    "body.moments": Key(unit="", size=3, help="principal moments A <= B <= C, any unit"),
    "body.omega0": Key(**SPIN, size=3, help="initial body angular velocity"),
    "body.attitude0": Key(**ANGLE, size=3, default=np.zeros(3), help="initial JPL 3-1-3 angles"),
}

VERDICT = Verdict("Euler's closed form", (
    Check("attitude", "attitude_max_error_vs_closed_form_rad", 1e-10, " rad",
          "dop853 at rtol 1e-13 over 100 periods: rounding and tolerance floor ~1e-11 rad "
          "(benchmarks/RESULTS.md)"),
    Check("ω relative", "omega_max_rel_error_vs_closed_form", 1e-10, "",
          "same floor, relative to |omega0|"),
))


def build(scenario):
    """For ``spinorbit bench``: (system, output times, error(solution) = max attitude error vs closed
    form, rad)."""
    from ...theory import FreeRigidBody

    moments, omega0 = scenario["body.moments"], scenario["body.omega0"]
    q0 = quat_from_euler313(*scenario["body.attitude0"])
    system = free_body(moments, q0, omega0, scenario.t_start)
    t = scenario.output_times()
    q_exact = FreeRigidBody(moments, omega0, q0).attitude(t - scenario.t_start)
    return system, t, lambda solution: float(quat_angle(solution.quaternion, q_exact).max())


def run(scenario):
    from ...theory import FreeRigidBody

    moments, omega0 = scenario["body.moments"], scenario["body.omega0"]
    q0 = quat_from_euler313(*scenario["body.attitude0"])
    try:
        exact = FreeRigidBody(moments, omega0, q0)
    except PhysicsError as exc:
        raise ScenarioError("body", {"moments": moments.tolist(), "omega0": omega0.tolist()},
                            f"0 < A <= B <= C and a non-zero omega0 ({exc})") from None
    system = free_body(moments, q0, omega0, scenario.t_start)
    t = scenario.output_times()
    solution, point = common.simulate_scenario(scenario, system, t)

    dt = solution.t - scenario.t_start
    omega_exact = exact.omega(dt)
    q_exact = exact.attitude(dt)
    omega_err = np.abs(solution.omega - omega_exact).max() / np.linalg.norm(omega0)
    attitude_err = quat_angle(solution.quaternion, q_exact) / ARCSEC
    comparison = {
        "regime": exact.regime,
        "period_d": exact.period,
        "two_T": exact.two_t,
        "k2": exact.m,
        "omega_max_rel_error_vs_closed_form": float(omega_err),
        "attitude_max_error_vs_closed_form_arcsec": float(attitude_err.max()),
        "attitude_max_error_vs_closed_form_rad": float(attitude_err.max() * ARCSEC),
    }
    table = common.attitude_table(solution)
    table["attitude_error"] = attitude_err * common.u().arcsec
    figures = {
        "omega": common.plot_omega(solution),
        "error_vs_closed_form": common.plot_series(
            solution.t - scenario.t_start, attitude_err,
            "days from start", "attitude error vs closed form [arcsec]"),
    }
    invariants = invariant_drift(moments, solution.quaternion, solution.omega)
    summary = {"comparison": comparison, "run": point, "invariants": invariants}
    return common.result(scenario, table, summary, figures, solution)
