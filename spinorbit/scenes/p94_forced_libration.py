"""Libration forced by an uneven orbit (Euler ch. 16 P94, §833-836) against the integrated body.

F moves in the body's equatorial plane with XF = delta t + alpha sin At and
1/s^3 = (1 + beta cos At)/f^3 (orbits.analytic.UnevenCircle).  The body starts
with A towards F and the spin §838 prescribes, so no free libration is excited;
Euler's zeta = A^2 alpha/(A^2 - 2n) sin At (+ the §835 sin 2At term) is compared
with the full 3-D rigid body.  The neglected terms are O(alpha beta^2, n zeta^3).
"""
import numpy as np

from ..base.constants import ARCSEC
from ..comparisons import forced_libration_p94 as vs
from ..scene.declaration import Outcome, Scene
from ..scene.params import Params, key, table
from ..scene.schema import ANGLE, DISTANCE, GM, RATE
from ..scene.verdict import Check, Verdict
from ..starts import idealised as start
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
    return start.forced_libration(p)


def compare_run(p, run):
    comparison, dt, zeta_num, zeta_second = vs.compare(p, run.solution, run.model.n)
    figures = {"zeta": common.plot_series(dt, np.array([zeta_num, zeta_second]) / ARCSEC, "days from start",
                                          "zeta = AF [arcsec]", ["integrated", "Euler §835"])}
    rad = common.u().rad
    return Outcome(comparison, {"zeta": zeta_num * rad, "zeta_euler": zeta_second * rad}, figures)


SCENE = Scene(P94ForcedLibrationParams, build, compare_run, VERDICT, time_scales=common.rigid_body_time_scales,
              taylor=True)
