"""Torque-free asymmetric rigid body against Euler's closed form (ch. 15 §808; Euler 1758 via Cayley).

Compares the integrated body angular velocity and attitude with the Jacobi
elliptic-function solution of spinorbit.analysis.theory.FreeRigidBody.  Euler's
equations need only 0 < A <= B <= C; the triangle inequality A + B >= C of a
real mass distribution is not required here, so that the classic
Hairer-Lubich-Wanner test case (moments 2/3, 1, 2) can be run as published.
"""
import numpy as np

from ..analysis.invariants import invariant_drift
from ..base.errors import PhysicsError, ScenarioError
from ..base.rotations import quat_angle, quat_from_euler313
from ..comparisons import free_body_closed_form as vs
from ..models.assemblies.idealised import free_body
from ..scene.declaration import Model, Outcome, Scene
from ..scene.params import Params, key, table
from ..scene.schema import ANGLE, SPIN
from ..scene.verdict import Check, Verdict
from . import common


@table
class BodyTable:
    moments: np.ndarray = key(unit="", size=3, help="principal moments A <= B <= C, any unit")
    omega0: np.ndarray = key(**SPIN, size=3, help="initial body angular velocity")
    attitude0: np.ndarray = key(**ANGLE, size=3, default=np.zeros(3), help="initial JPL 3-1-3 angles")


@table
class FreeBodyParams(Params):
    body: BodyTable


VERDICT = Verdict("Euler's closed form", (
    Check("attitude", vs.ATTITUDE_MAX_ERROR_RAD, 1e-10, " rad",
          "dop853 at rtol 1e-13 over 100 periods: rounding and tolerance floor ~1e-11 rad "
          "(benchmarks/RESULTS.md)"),
    Check("ω relative", vs.OMEGA_MAX_REL_ERROR, 1e-10, "",
          "same floor, relative to |omega0|"),
))


def build(p, times):
    """The free body and its closed form (theory.FreeRigidBody) from the same start."""
    from ..analysis.theory import FreeRigidBody

    q0 = quat_from_euler313(*p.body.attitude0)
    try:
        exact = FreeRigidBody(p.body.moments, p.body.omega0, q0)
    except PhysicsError as exc:
        raise ScenarioError("body", {"moments": p.body.moments.tolist(), "omega0": p.body.omega0.tolist()},
                            f"0 < A <= B <= C and a non-zero omega0 ({exc})") from None
    return Model(free_body(p.body.moments, q0, p.body.omega0, p.span.start), exact=exact)


def compare_run(p, run):
    solution = run.solution
    comparison, dt, attitude_err = vs.compare(p, solution, run.model.exact)
    figures = {"omega": common.plot_omega(solution),
               "error_vs_closed_form": common.plot_series(dt, attitude_err, "days from start",
                                                          "attitude error vs closed form [arcsec]")}
    invariants = invariant_drift(p.body.moments, solution.quaternion, solution.omega)
    return Outcome(comparison, columns={"attitude_error": attitude_err * common.u().arcsec}, figures=figures,
                   sections={"invariants": invariants})


def bench(p, model, times):
    """Max attitude error against the closed form, rad."""
    q_exact = model.exact.attitude(times - p.span.start)
    return lambda solution: float(quat_angle(solution.quaternion, q_exact).max())


SCENE = Scene(FreeBodyParams, build, compare_run, VERDICT, time_scales=common.rigid_body_time_scales,
              bench=bench,
              taylor=True)
