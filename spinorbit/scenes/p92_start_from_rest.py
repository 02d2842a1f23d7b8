"""First motion of a body at rest (Euler ch. 16 P92, §820-823; ch. 15 §806) against the integrator.

A body at rest with a fixed centre of forces F (direction given in body axes)
begins to turn about the axis (cos alpha, cos beta, cos gamma) ~ (P/A, Q/B, R/C)
with d gamma'/dt = |(P/A, Q/B, R/C)|.  The integrator's omega(t)/t at the
first output step gives the same axis and rate to O(t).
"""
import math

import numpy as np

from ..base.constants import ARCSEC
from ..models.assemblies.idealised import under_point_masses
from ..scene.declaration import Model, Outcome, Scene
from ..scene.params import Params, key, table
from ..scene.verdict import Check, Verdict
from . import common


@table
class BodyTable:
    moments: np.ndarray = key(unit="", size=3, help="principal moments A <= B <= C, any unit")


@table
class ForceTable:
    direction: np.ndarray = key(unit="", size=3, direction=True,
                                help="direction of F in body principal axes")


@table
class P92StartFromRestParams(Params):
    body: BodyTable
    orbit: common.CentreOfForcesTable
    force: ForceTable


VERDICT = Verdict("Euler's first motion (§821-823)", (
    Check("axis", "axis_error_arcsec", 1e-3, "″",
          "omega(t)/t turns by O(t): ~1e-4 of the 1e-4 d first step"),
    Check("rate relative", "rate_rel_error", 1e-9, "",
          "omega(t)/t = d gamma'/dt + O(t^2) for a body at rest"),
))


def build(p, times):
    """The body at rest, F fixed (rate 0) at ``force.direction``: a circle point (cos a, sin a cos i,
    sin a sin i)."""
    from ..orbits.analytic import CircularOrbits

    body = common.rigid_body(p.body.moments)
    u = p.force.direction / np.linalg.norm(p.force.direction)
    orbit = CircularOrbits(("F",), [p.orbit.gm], [p.orbit.radius], [0.0], phase=[math.acos(u[0])],
                           inclination=[math.atan2(u[2], u[1])])
    system = under_point_masses(body.moments, orbit, [1.0, 0, 0, 0], np.zeros(3), p.span.start, "body at rest")
    return Model(system, direction=u)


def compare_run(p, run):
    from ..analysis.theory import start_from_rest

    solution = run.solution
    axis, cos_of, rate = start_from_rest(p.body.moments, run.model.direction, p.orbit.gm, p.orbit.radius)
    dt1 = solution.t[1] - solution.t[0]
    w1 = solution.omega[1]
    axis_num = w1 / np.linalg.norm(w1)
    comparison = {
        "axis_cos_alpha": float(axis[0]), "axis_cos_beta": float(axis[1]), "axis_cos_gamma": float(axis[2]),
        "cos_OF": cos_of,
        "rate_euler_rad_per_d2": rate,
        "rate_integrated_rad_per_d2": float(np.linalg.norm(w1) / dt1),
        "rate_rel_error": float(abs(np.linalg.norm(w1) / dt1 / rate - 1)),
        # atan2 of |a x b| and a.b: acos(a.b) floors at sqrt(2 eps) = 0.003" near zero
        "axis_error_arcsec": float(
            math.atan2(np.linalg.norm(np.cross(axis_num, axis)), axis_num @ axis) / ARCSEC),
        "first_step_d": float(dt1),
    }
    return Outcome(comparison, figures={"omega": common.plot_omega(solution)})


SCENE = Scene(P92StartFromRestParams, build, compare_run, VERDICT, time_scales=common.rigid_body_time_scales,
              taylor=True)
