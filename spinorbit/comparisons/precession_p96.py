"""p96_precession's comparison: the figure axis's regression and 2 phi inequalities, fitted to the integrated
ZA and XZA (spinorbit.analysis.figure_axis.fit_angles), against Euler's closed forms (§846-847) in his text's
version and with the pole's free rotation (the gyroscopic one), or at eps = 2 delta the secular growth of ZA's
2 phi term against §849's singular solution."""
import math

from ..analysis.figure_axis import fit_angles
from ..base.constants import ARCSEC

EULER, GYROSCOPIC = "euler", "gyroscopic"          # the closed forms compared: Euler's text's, and with aa/cc


def precession_rate_rel_error(model):
    """The summary's key of the measured regression rate's error relative to ``model``'s closed form."""
    return f"precession_rate_{model}_rel_error"


def za_half_range(model):
    """The summary's key of ``model``'s half range of ZA's 2 phi inequality (arcsec)."""
    return f"za_2phi_half_range_{model}_arcsec"


def xza_amplitude(model):
    """The summary's key of ``model``'s amplitude of XZA's 2 phi inequality (arcsec)."""
    return f"xza_2phi_amplitude_{model}_arcsec"


# The metrics the verdict judges (the summary's comparison keys)
RESONANCE_DETECTED = "resonance_detected"
ZA_2PHI_GROWTH_REL_ERROR = "za_2phi_growth_rel_error"
ZA_2PHI_HALF_RANGE_MEASURED_ARCSEC = za_half_range("measured")
XZA_2PHI_AMPLITUDE_MEASURED_ARCSEC = xza_amplitude("measured")


def compare(params, model, solution):
    """(metrics, not measured, days from span.start, ZA, XZA (rad)) of the run ``solution`` of ``model`` (the
    scene's: big_n, euler, true, resonance)."""
    delta, eps = params.orbit.rate, params.body.spin
    euler, true, resonance = model.euler, model.true, model.resonance
    comparison = {"N_rad_per_d": model.big_n, "eps_over_delta": eps / delta}
    dt, p, lam, lam_fit, p_fit = fit_angles(solution, params.span.start, delta, true.eps_f,
                                            resonant=resonance is not None)
    if resonance is None:
        comparison.update({
            RESONANCE_DETECTED: False,
            "precession_rate_measured_arcsec_per_d": float(-lam_fit[1] / ARCSEC),
            ZA_2PHI_HALF_RANGE_MEASURED_ARCSEC: float(abs(p_fit[1]) / ARCSEC),
            XZA_2PHI_AMPLITUDE_MEASURED_ARCSEC: float(abs(lam_fit[2]) / ARCSEC),
            "diurnal_nutation_measured_arcsec": float(math.hypot(p_fit[3], p_fit[4]) / ARCSEC)})
        for name, closed in ((EULER, euler), (GYROSCOPIC, true)):
            comparison.update({
                f"precession_rate_{name}_arcsec_per_d": closed.precession_rate / ARCSEC,
                precession_rate_rel_error(name): float(closed.precession_rate / -lam_fit[1] - 1),
                za_half_range(name): closed.inequalities()["za_half_range"] / ARCSEC,
                xza_amplitude(name): closed.inequalities()["xza_amplitude"] / ARCSEC})
    else:
        # §849: ZA's 2 phi term grows like |a| delta t; fit (c + g t) cos 2phi + (c' + g' t) sin 2phi.
        growth, secular = math.hypot(p_fit[3], p_fit[4]), euler.secular()
        comparison.update({
            RESONANCE_DETECTED: True, "resonance_message": str(resonance),
            "za_2phi_growth_measured_arcsec_per_d": growth / ARCSEC,
            "za_2phi_growth_euler_849_arcsec_per_d": secular["growth_rate"] / ARCSEC,
            ZA_2PHI_GROWTH_REL_ERROR: growth / secular["growth_rate"] - 1,
            "detuning_eps_aa_over_cc_minus_2delta_rad_per_d": true.eps_f - 2 * delta,
        })
    not_measured = unsupported(comparison, dt[-1], delta)
    return comparison, not_measured, dt, p, lam


def unsupported(comparison, span_d, delta):
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
