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
    Check("pole shift relative", "pole_shift_rel_error", 2e-3, "",
          "O((aa - cc)/cc gamma' t) over 0.002 d: the free rotation §840 drops"),
    Check("spin change", "spin_rel_change", 1e-9, "", "§841: gamma' constant; integration floor"),
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
    from ..analysis.theory import pole_rates_symmetric

    solution, (cc, _, aa) = run.solution, p.body.moments
    gamma, alpha, rho = p.body.spin, p.body.pole_offset, p.body.pole_angle
    dt = solution.t - p.span.start
    pole = solution.omega / np.linalg.norm(solution.omega, axis=1, keepdims=True)
    shift = pole[:, :2] - pole[0, :2]                              # (xi, eta) displacement of O
    d_alpha, alpha_d_rho = pole_rates_symmetric(aa, cc, gamma, p.orbit.gm, p.orbit.radius, rho,
                                                run.model.u_euler)
    rate = np.array([d_alpha * math.cos(rho) - alpha_d_rho * math.sin(rho),
                     d_alpha * math.sin(rho) + alpha_d_rho * math.cos(rho)])
    predicted = np.outer(dt, rate)
    error = np.linalg.norm(shift - predicted, axis=1).max() / np.linalg.norm(predicted[-1])
    comparison = {
        "d_alpha_dt_euler_rad_per_d": d_alpha,
        "alpha_d_rho_dt_euler_rad_per_d": alpha_d_rho,
        "pole_shift_integrated_rad": float(np.linalg.norm(shift[-1])),
        "pole_shift_euler_rad": float(np.linalg.norm(predicted[-1])),
        "pole_shift_rel_error": float(error),
        "free_rotation_over_torque_rate": float((aa - cc) / cc * gamma * alpha / np.linalg.norm(rate)),
        "spin_rel_change": float(abs(np.linalg.norm(solution.omega[-1]) / gamma - 1)),
    }
    shifts = np.array([shift[:, 0], predicted[:, 0], shift[:, 1], predicted[:, 1]])
    figures = {"pole": common.plot_series(dt, shifts, "days from start", "pole shift [rad]",
                                          ["xi integrated", "xi §843a", "eta integrated", "eta §843a"])}
    return Outcome(comparison, figures=figures)


SCENE = Scene(P95NearPrincipalAxisParams, build, compare_run, VERDICT, time_scales=common.rigid_body_time_scales,
              taylor=True)
