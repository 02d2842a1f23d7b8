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
import math

import numpy as np

from ..analysis.figure_axis import fit_angles
from ..base.constants import ARCSEC
from ..base.errors import ResonanceError, ScenarioError
from ..models.assemblies.idealised import under_point_masses
from ..scene.declaration import Model, Outcome, Scene
from ..scene.params import Params, key, table
from ..scene.schema import ANGLE, SPIN
from ..scene.verdict import Check, Verdict
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
    if comparison.get("resonance_detected"):
        return Verdict("Euler's singular solution (§849)", (
            Check("2φ growth relative", "za_2phi_growth_rel_error", 0.01, "",
                  "§849 is first order in the detuning and in N/delta"),))
    return Verdict("Euler's P96 closed forms (§846-847)", (
        Check("precession rate relative", "precession_rate_gyroscopic_rel_error", 2e-3, "", _SECOND_ORDER),
        Check("ZA 2φ relative", "za_2phi_half_range_measured_arcsec", 5e-3, "", _SECOND_ORDER,
              versus="za_2phi_half_range_gyroscopic_arcsec", relative=True),
        Check("XZA 2φ relative", "xza_2phi_amplitude_measured_arcsec", 5e-3, "", _SECOND_ORDER,
              versus="xza_2phi_amplitude_gyroscopic_arcsec", relative=True)))


def build(p, times):
    """The spinner on Euler's forced solution (§844), or at its pole where the formulas fail (§849); the
    closed forms of Euler's text and with the pole's free rotation (``true``)."""
    from ..analysis.theory import SymmetricPrecession, p96_initial_state, precession_constant
    from ..orbits.analytic import CircularOrbits

    body = common.rigid_body(p.body.moments)
    cc, aa = body.moments[0], body.moments[2]
    if not (abs(body.moments[1] - cc) <= 1e-12 * aa and aa > cc):
        raise ScenarioError("body.moments", body.moments.tolist(),
                            "a symmetric oblate body [cc, cc, aa] with aa > cc")
    eps, n, o = p.body.spin, p.body.obliquity, p.orbit
    big_n = precession_constant(o.gm, o.radius, eps, aa, cc)
    euler = SymmetricPrecession(eps, o.rate, big_n, n)
    true = SymmetricPrecession(eps, o.rate, big_n, n, ratio=aa / cc)
    try:
        e, f, _ = true.coefficients()
        x0, resonance = e + f, None
    except ResonanceError as exc:
        x0, resonance = 0.0, exc
    q0, omega0 = p96_initial_state(n, eps, x0, 0.0)
    orbit = CircularOrbits(("F",), [o.gm], [o.radius], [o.rate], phase=[-o.rate * p.span.start])
    system = under_point_masses(body.moments, orbit, q0, omega0, p.span.start, "symmetric spinner")
    return Model(system, big_n=big_n, euler=euler, true=true, resonance=resonance)


def compare_run(params, run):
    m, delta, eps = run.model, params.orbit.rate, params.body.spin
    euler, true, resonance = m.euler, m.true, m.resonance
    comparison = {"N_rad_per_d": m.big_n, "eps_over_delta": eps / delta}
    dt, p, lam, lam_fit, p_fit = fit_angles(run.solution, params.span.start, delta, true.eps_f,
                                            resonant=resonance is not None)
    if resonance is None:
        comparison.update({
            "resonance_detected": False,
            "precession_rate_measured_arcsec_per_d": float(-lam_fit[1] / ARCSEC),
            "za_2phi_half_range_measured_arcsec": float(abs(p_fit[1]) / ARCSEC),
            "xza_2phi_amplitude_measured_arcsec": float(abs(lam_fit[2]) / ARCSEC),
            "diurnal_nutation_measured_arcsec": float(math.hypot(p_fit[3], p_fit[4]) / ARCSEC)})
        for name, model in (("euler", euler), ("gyroscopic", true)):
            comparison.update({
                f"precession_rate_{name}_arcsec_per_d": model.precession_rate / ARCSEC,
                f"precession_rate_{name}_rel_error": float(model.precession_rate / -lam_fit[1] - 1),
                f"za_2phi_half_range_{name}_arcsec": model.inequalities()["za_half_range"] / ARCSEC,
                f"xza_2phi_amplitude_{name}_arcsec": model.inequalities()["xza_amplitude"] / ARCSEC})
    else:
        # §849: ZA's 2 phi term grows like |a| delta t; fit (c + g t) cos 2phi + (c' + g' t) sin 2phi.
        growth, secular = math.hypot(p_fit[3], p_fit[4]), euler.secular()
        comparison.update({
            "resonance_detected": True, "resonance_message": str(resonance),
            "za_2phi_growth_measured_arcsec_per_d": growth / ARCSEC,
            "za_2phi_growth_euler_849_arcsec_per_d": secular["growth_rate"] / ARCSEC,
            "za_2phi_growth_rel_error": growth / secular["growth_rate"] - 1,
            "detuning_eps_aa_over_cc_minus_2delta_rad_per_d": true.eps_f - 2 * delta,
        })
    not_measured = _unsupported(comparison, dt[-1], delta)
    figures = {"ZA": common.plot_series(dt, np.degrees(p), "days from start", "ZA [deg]"),
               "XZA": common.plot_series(dt, np.degrees(lam), "days from start", "XZA [deg]")}
    return Outcome(comparison, {"ZA": p * common.u().rad, "XZA": lam * common.u().rad}, figures,
                   not_measured=not_measured)


def _unsupported(comparison, span_d, delta):
    """Blank the fitted values (None, with the reason) when the span is shorter than one orbit of F:
    the fit cannot then tell the precession from the 2 phi inequality."""
    orbit_d = 2 * math.pi / abs(delta) if delta else math.inf
    if span_d >= orbit_d:
        return {}
    reason = (f"not measured: the {span_d:.6g} d span is shorter than one orbit of F ({orbit_d:.6g} d), "
              "so the fit cannot separate the precession from the 2 phi inequality; lengthen span.end")
    fitted = [key for key in comparison if "measured" in key or key.endswith("rel_error")]
    comparison.update(dict.fromkeys(fitted))
    return {f"comparison.{key}": reason for key in fitted}


SCENE = Scene(P96PrecessionParams, build, compare_run, verdict, time_scales=common.rigid_body_time_scales,
              taylor=True)
