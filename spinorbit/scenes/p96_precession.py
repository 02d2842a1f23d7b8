"""Precession and nutation of a symmetric spinner (Euler ch. 16 P96, §844-849) against integration.

A body with two equal moments cc < aa (oblate; aa about its figure axis, our
z) spins at eps about an axis near its figure axis, at the mean angle n from
the pole Z of the orbit of F (a uniform circle at rate delta, the x-y plane).
Euler's theory: the figure axis A regresses about Z at N cos n (§846), with
2 phi inequalities in ZA and XZA (§847, phi = FZA), and at eps = 2 delta the
formulas fail (§849): there ``SymmetricPrecession.coefficients`` raises
ResonanceError; the scene reports it and compares the secular growth of the
2 phi term in ZA with §849's singular solution.

Both Euler's text (eps in the pole equations) and the version with the pole's
free rotation in the body (eps aa/cc, which §841 drops) are compared.
"""

import numpy as np

from ..comparisons import precession_p96 as vs
from ..scene.declaration import Outcome, Scene
from ..scene.params import Params, key, table
from ..scene.schema import ANGLE, SPIN
from ..scene.verdict import Check, Verdict
from ..starts import idealised as start
from . import common


@table
class BodyTable:
    moments: np.ndarray = key(unit="", size=3, help="principal moments cc = cc < aa (symmetric, oblate)")
    spin: float = key(**SPIN, help="spin rate eps about the figure axis")
    obliquity: float = key(**ANGLE, help="initial angle n between the figure axis A and the orbit pole Z")


@table
class P96PrecessionParams(Params):
    body: BodyTable
    orbit: common.CircularCentreTable


_SECOND_ORDER = ("Euler's theory is first order in N/delta and drops eps aa/cc - eps; "
                 "2e-3 covers the remainder")


def verdict(p, comparison):
    """Away from resonance: rate and 2 phi terms vs the closed form; where theory.SymmetricPrecession
    finds eps aa/cc = 2 delta (``resonance_detected``): §849's growth."""
    if comparison.get(vs.RESONANCE_DETECTED):
        return Verdict("Euler's singular solution (§849)", (
            Check("2φ growth relative", vs.ZA_2PHI_GROWTH_REL_ERROR, 0.01, "",
                  "§849 is first order in the detuning and in N/delta"),))
    return Verdict("Euler's P96 closed forms (§846-847)", (
        Check("precession rate relative", vs.precession_rate_rel_error(vs.GYROSCOPIC), 2e-3, "", _SECOND_ORDER),
        Check("ZA 2φ relative", vs.ZA_2PHI_HALF_RANGE_MEASURED_ARCSEC, 5e-3, "", _SECOND_ORDER,
              versus=vs.za_half_range(vs.GYROSCOPIC), relative=True),
        Check("XZA 2φ relative", vs.XZA_2PHI_AMPLITUDE_MEASURED_ARCSEC, 5e-3, "", _SECOND_ORDER,
              versus=vs.xza_amplitude(vs.GYROSCOPIC), relative=True)))


def build(p, times):
    """The spinner on Euler's forced solution (§844), or at its pole where the formulas fail (§849); the
    closed forms of Euler's text and with the pole's free rotation (``true``)."""
    return start.symmetric_spinner(p)


def compare_run(p, run):
    comparison, not_measured, dt, za, xza = vs.compare(p, run.model, run.solution)
    figures = {"ZA": common.plot_series(dt, np.degrees(za), "days from start", "ZA [deg]"),
               "XZA": common.plot_series(dt, np.degrees(xza), "days from start", "XZA [deg]")}
    return Outcome(comparison, {"ZA": za * common.u().rad, "XZA": xza * common.u().rad}, figures,
                   not_measured=not_measured)


SCENE = Scene(P96PrecessionParams, build, compare_run, verdict, time_scales=common.rigid_body_time_scales,
              taylor=True)
