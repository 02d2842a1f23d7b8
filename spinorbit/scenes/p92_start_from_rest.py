"""First motion of a body at rest (Euler ch. 16 P92, §820-823; ch. 15 §806) against the integrator.

A body at rest with a fixed centre of forces F (direction given in body axes)
begins to turn about the axis (cos alpha, cos beta, cos gamma) ~ (P/A, Q/B, R/C)
with d gamma'/dt = |(P/A, Q/B, R/C)|.  The integrator's omega(t)/t at the
first output step gives the same axis and rate to O(t).
"""

import numpy as np

from ..comparisons import start_from_rest_p92 as vs
from ..scene.declaration import Outcome, Scene
from ..scene.params import Params, key, table
from ..scene.verdict import Check, Verdict
from ..starts import idealised as start
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
    Check("axis", vs.AXIS_ERROR_ARCSEC, 1e-3, "″",
          "omega(t)/t turns by O(t): ~1e-4 of the 1e-4 d first step"),
    Check("rate relative", vs.RATE_REL_ERROR, 1e-9, "",
          "omega(t)/t = d gamma'/dt + O(t^2) for a body at rest"),
))


def build(p, times):
    """The body at rest, F fixed (rate 0) at ``force.direction``: a circle point (cos a, sin a cos i,
    sin a sin i)."""
    return start.at_rest(p)


def compare_run(p, run):
    comparison = vs.compare(p, run.solution, run.model.direction)
    return Outcome(comparison, figures={"omega": common.plot_omega(run.solution)})


SCENE = Scene(P92StartFromRestParams, build, compare_run, VERDICT, time_scales=common.rigid_body_time_scales,
              taylor=True)
