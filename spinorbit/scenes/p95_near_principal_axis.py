"""Motion of the pole near a principal axis (Euler ch. 16 P95, §840-843a) against the full equations.

A symmetric body (Euler's bb = cc, our x and y; his singular axis A is our z)
spins at gamma' about a pole O at a small arc alpha = AO, angle rho = BAO,
with a fixed centre of forces F.  §841: gamma' does not change; §843a gives
d alpha/dt and alpha d rho/dt.  As a displacement of O in the tangent plane
at A, (xi, eta) = alpha (cos rho, sin rho), they are compared with the
integrated pole over a short span; the free rotation of O about A at
(aa - cc)/cc gamma', which §840 drops by taking y = z = 0, limits the
agreement to O(alpha (aa - cc) gamma'^2 s^3/GM) and O((aa - cc)/cc gamma' t).
"""

import numpy as np

from ..comparisons import pole_rates_p95 as vs
from ..scene.declaration import Outcome, Scene
from ..scene.params import Params, key, table
from ..scene.schema import ANGLE, SPIN
from ..scene.verdict import Check, Verdict
from ..starts import idealised as start
from . import common


@table
class BodyTable:
    moments: np.ndarray = key(unit="", size=3, help="symmetric body [cc, cc, aa]")
    spin: float = key(**SPIN, help="angular speed gamma'")
    pole_offset: float = key(**ANGLE, help="alpha = AO, arc from the figure axis to the rotation pole")
    pole_angle: float = key(**ANGLE, default=0.0, help="rho = angle BAO")


@table
class ForceTable:
    direction: np.ndarray = key(unit="", size=3, direction=True,
                                help="(cos AF, cos BF, cos CF) in Euler's axes A (= our z), B, C")


@table
class P95NearPrincipalAxisParams(Params):
    body: BodyTable
    orbit: common.CentreOfForcesTable
    force: ForceTable


VERDICT = Verdict("Euler's pole rates (§843a)", (
    Check("pole shift relative", vs.POLE_SHIFT_REL_ERROR, 2e-3, "",
          "O((aa - cc)/cc gamma' t) over 0.002 d: the free rotation §840 drops"),
    Check("spin change", vs.SPIN_REL_CHANGE, 1e-9, "", "§841: gamma' constant; integration floor"),
))


def build(p, times):
    """The symmetric body spinning about a pole alpha from its figure axis, F fixed at ``force.direction``."""
    return start.near_principal_axis(p)


def compare_run(p, run):
    comparison, dt, shift, predicted = vs.compare(p, run.solution, run.model.u_euler)
    shifts = np.array([shift[:, 0], predicted[:, 0], shift[:, 1], predicted[:, 1]])
    figures = {"pole": common.plot_series(dt, shifts, "days from start", "pole shift [rad]",
                                          ["xi integrated", "xi §843a", "eta integrated", "eta §843a"])}
    return Outcome(comparison, figures=figures)


SCENE = Scene(P95NearPrincipalAxisParams, build, compare_run, VERDICT, time_scales=common.rigid_body_time_scales,
              taylor=True)
