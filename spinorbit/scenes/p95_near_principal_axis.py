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
import math

import numpy as np

from ..base.errors import ScenarioError
from ..comparisons import pole_rates_p95 as vs
from ..models.assemblies.idealised import under_point_masses
from ..scene.declaration import Model, Outcome, Scene
from ..scene.params import Params, key, table
from ..scene.schema import ANGLE, SPIN
from ..scene.verdict import Check, Verdict
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
    from ..orbits.analytic import CircularOrbits

    body, b = common.rigid_body(p.body.moments), p.body
    cc, aa = body.moments[0], body.moments[2]
    if abs(body.moments[1] - cc) > 1e-12 * aa:
        raise ScenarioError("body.moments", body.moments.tolist(),
                            "a symmetric body [cc, cc, aa] (§841: bb = cc)")
    u_euler = p.force.direction / np.linalg.norm(p.force.direction)
    u = np.array([u_euler[1], u_euler[2], u_euler[0]])          # our (x, y, z) = Euler's (B, C, A)
    orbit = CircularOrbits(("F",), [p.orbit.gm], [p.orbit.radius], [0.0], phase=[math.acos(u[0])],
                           inclination=[math.atan2(u[2], u[1])])
    alpha, rho = b.pole_offset, b.pole_angle
    omega0 = b.spin * np.array([math.sin(alpha) * math.cos(rho), math.sin(alpha) * math.sin(rho),
                                math.cos(alpha)])
    system = under_point_masses(body.moments, orbit, [1.0, 0, 0, 0], omega0, p.span.start, "near principal axis")
    return Model(system, u_euler=u_euler)


def compare_run(p, run):
    comparison, dt, shift, predicted = vs.compare(p, run.solution, run.model.u_euler)
    shifts = np.array([shift[:, 0], predicted[:, 0], shift[:, 1], predicted[:, 1]])
    figures = {"pole": common.plot_series(dt, shifts, "days from start", "pole shift [rad]",
                                          ["xi integrated", "xi §843a", "eta integrated", "eta §843a"])}
    return Outcome(comparison, figures=figures)


SCENE = Scene(P95NearPrincipalAxisParams, build, compare_run, VERDICT, time_scales=common.rigid_body_time_scales,
              taylor=True)
