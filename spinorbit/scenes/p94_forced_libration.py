"""Libration forced by an uneven orbit (Euler ch. 16 P94, §833-836) against the integrated body.

F moves in the body's equatorial plane with XF = delta t + alpha sin At and
1/s^3 = (1 + beta cos At)/f^3 (orbits.analytic.UnevenCircle).  The body starts
with A towards F and the spin §838 prescribes, so no free libration is excited;
Euler's zeta = A^2 alpha/(A^2 - 2n) sin At (+ the §835 sin 2At term) is compared
with the full 3-D rigid body.  The neglected terms are O(alpha beta^2, n zeta^3).
"""
import numpy as np

from ..analysis.planar_libration import planar_system
from ..base.constants import ARCSEC
from ..base.errors import ScenarioError
from ..comparisons import forced_libration_p94 as vs
from ..scene.declaration import Model, Outcome, Scene
from ..scene.params import Params, key, table
from ..scene.schema import ANGLE, DISTANCE, GM, RATE
from ..scene.verdict import Check, Verdict
from . import common


@table
class BodyTable:
    moments: np.ndarray = key(unit="", size=3, help="principal moments A < B <= C, any unit")


@table
class OrbitTable:
    gm: float = key(**GM, help="GM of the centre of forces")
    f: float = key(**DISTANCE, help="mean distance f")
    rate: float = key(**RATE, help="mean angular speed delta of F")
    alpha: float = key(**ANGLE, help="amplitude of the inequality of XF")
    beta: float = key(unit="", min=-0.5, max=0.5, help="amplitude of the inequality of 1/s^3")
    frequency: float = key(**RATE, help="Euler's A, the frequency of the inequality")


@table
class P94ForcedLibrationParams(Params):
    body: BodyTable
    orbit: OrbitTable


VERDICT = Verdict("Euler's forced libration to second order (§835)", (
    Check("zeta relative", vs.ZETA_ERROR_SECOND_ORDER_REL, 3e-4, "",
          "the neglected terms O(alpha beta^2, n zeta^3) relative to the amplitude"),
))


def build(p, times):
    """The body with A towards F and the spin §838 prescribes (no free libration excited)."""
    from ..analysis.theory import forced_libration_initial_rate, libration_n
    from ..orbits.analytic import UnevenCircle

    body, o = common.rigid_body(p.body.moments), p.orbit
    n = libration_n(body.moments, o.gm, o.f)
    orbit = UnevenCircle(("F",), [o.gm], [o.f], [o.rate], [o.alpha], [o.beta], [o.frequency])
    if p.span.start != 0.0:
        raise ScenarioError("span.start", p.span.start,
                            "'2000-01-01T12:00:00' (J2000): Euler's inequality sin At is timed from t = 0")
    zeta_dot0 = forced_libration_initial_rate(n, o.frequency, o.alpha, o.beta)
    start_rate = zeta_dot0 - o.frequency * o.alpha
    return Model(planar_system(body.moments, orbit, p.span.start, 0.0, start_rate, o.rate), n=n)


def compare_run(p, run):
    comparison, dt, zeta_num, zeta_second = vs.compare(p, run.solution, run.model.n)
    figures = {"zeta": common.plot_series(dt, np.array([zeta_num, zeta_second]) / ARCSEC, "days from start",
                                          "zeta = AF [arcsec]", ["integrated", "Euler §835"])}
    rad = common.u().rad
    return Outcome(comparison, {"zeta": zeta_num * rad, "zeta_euler": zeta_second * rad}, figures)


SCENE = Scene(P94ForcedLibrationParams, build, compare_run, VERDICT, time_scales=common.rigid_body_time_scales,
              taylor=True)
