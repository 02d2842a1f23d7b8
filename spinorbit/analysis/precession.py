"""Precession and nutation of a pole, fitted and set beside a reference's.

Layer 2 (numpy).  A pole's Fukushima-Williams angles about a mean pole, dpsi = psi - psi_bar
and deps = eps - eps_A (rad), are fitted with a quadratic in T from J2000 and the nutation
arguments (harmonics.fit_harmonics; the arguments come from references.arguments).  A
precession rate needs RATE_MIN_SPAN_D: over a shorter span the 18.6-yr nutation aliases into it.
"""
import numpy as np

from ..base.constants import ARCSEC, JULIAN_CENTURY_D, MAS
from .harmonics import fit_harmonics

RATE_MIN_SPAN_D = 50 * 365.25
# The rates compare_with_iau compares (the summary's comparison keys, read by the Earth's verdict)
PSI_RATE_MINUS_IAU_ARCSEC_CY, OBLIQUITY_RATE_MINUS_IAU_ARCSEC_CY = ("psi_rate_minus_iau_arcsec_cy",
                                                                    "obliquity_rate_minus_iau_arcsec_cy")


def rate_refusal(span_d):
    """Why a span of ``span_d`` days cannot give a precession rate, or None if it can."""
    if span_d >= RATE_MIN_SPAN_D:
        return None
    return (f"a precession rate needs a span of {RATE_MIN_SPAN_D:.0f} d (50 yr; shorter ones alias the 18.6-yr "
            f"nutation into it), the run has {span_d:.0f} d")


def fit_pole(t_tdb_d, dpsi, deps, arguments, separate=True):
    """(fit of dpsi, fit of deps): HarmonicFit, quadratic in T from J2000, rad (``separate``: spans.resolvable)."""
    return tuple(fit_harmonics(t_tdb_d, v, arguments, degree=2, separate=separate) for v in (dpsi, deps))


def compare_with_iau(t_tdb_d, model, reference, arguments, published):
    """A model's precession and nutation fitted beside a reference's: ``model``, ``reference`` = (dpsi, deps)
    about the same mean pole (rad), ``arguments`` as for fit_pole, ``published`` = {term: (dpsi sin,
    deps cos) arcsec}.

    Returns (comparison, not_measured, mean): the rate differences in longitude and obliquity ("/cy,
    None under RATE_MIN_SPAN_D); for each published term the model's coefficients, the reference's fitted
    alike (``_iau2000a_arcsec``: the fit takes the term's unresolved partners, so it is not the printed
    coefficient), the published ones (``_iau2000a_published_arcsec``) and model - reference (mas, the
    difference of the first two); in not_measured why a rate or term is not given (the span it needs);
    and the model's mean pole minus the reference's, (dpsi, deps) rad at the times (the polynomials).
    """
    fits = fit_pole(t_tdb_d, *model, arguments)
    refs = fit_pole(t_tdb_d, *reference, arguments)
    comparison = {PSI_RATE_MINUS_IAU_ARCSEC_CY: (fits[0].poly[1] - refs[0].poly[1]) / ARCSEC,
                  OBLIQUITY_RATE_MINUS_IAU_ARCSEC_CY: (fits[1].poly[1] - refs[1].poly[1]) / ARCSEC}
    not_measured = {}
    if why := rate_refusal(float(np.ptp(t_tdb_d))):
        not_measured = {f"comparison.{key}": why for key in comparison}
        comparison = dict.fromkeys(comparison)
    for term, (psi_pub, eps_pub) in published.items():
        key = "nutation_" + term.replace(" ", "").replace(".", "_")
        if fits[0].sin[term] is None:
            not_measured[f"comparison.{key}"] = fits[0].refused[term]
            continue
        for angle, trig, i, pub in (("dpsi", "sin", 0, psi_pub), ("deps", "cos", 1, eps_pub)):
            value, ref = getattr(fits[i], trig)[term] / ARCSEC, getattr(refs[i], trig)[term] / ARCSEC
            comparison.update({f"{key}_{angle}_model_arcsec": value, f"{key}_{angle}_iau2000a_arcsec": ref,
                               f"{key}_{angle}_iau2000a_published_arcsec": pub,
                               f"{key}_{angle}_model_minus_iau_mas": (value - ref) * 1000})
    return comparison, not_measured, tuple(mean_pole_offset(t_tdb_d, fit) for fit in fits)


def mean_pole_offset(t_tdb_d, fit):
    """The polynomial part of a fit at the times, rad: the model's mean pole minus the reference's."""
    return ((np.asarray(t_tdb_d) / JULIAN_CENTURY_D)[:, None] ** np.arange(len(fit.poly))) @ np.array(fit.poly)


def periodic_part(fit, phases):
    """The fitted periodic terms at one time, rad: sum s_k sin a_k + c_k cos a_k; ``phases`` name -> a_k."""
    return sum(fit.sin[k] * np.sin(a) + fit.cos[k] * np.cos(a) for k, a in phases.items() if fit.sin[k] is not None)


def term_table(fits, terms):
    """row -> part -> model -> coefficient (mas), as IAU 2000A writes them: dpsi = in sin + out cos,
    deps = in cos + out sin.  ``fits`` = {model: fit_pole result}, ``terms`` = {row: argument name};
    a term not fitted is None."""
    parts = {"dpsi_in": (0, "sin"), "dpsi_out": (0, "cos"), "deps_in": (1, "cos"), "deps_out": (1, "sin")}
    value = lambda fit, trig, name: None if getattr(fit, trig)[name] is None else getattr(fit, trig)[name] / MAS
    return {row: {part: {model: value(pair[i], trig, name) for model, pair in fits.items()}
                  for part, (i, trig) in parts.items()} for row, name in terms.items()}


def node_rate(t_tdb_d, poles, ecliptic_pole, periodic=None):
    """Mean rate (rad per Julian century) of the longitude of the equator's ascending node on a fixed
    ecliptic, for poles (n, 3) in the ecliptic's frame; fitted linearly with the ``periodic`` arguments
    (name -> (phase, rate)), positive for a regression (precession)."""
    x = np.cross([0.0, 0.0, 1.0], ecliptic_pole)
    x /= np.linalg.norm(x)
    node = np.unwrap(np.arctan2(poles @ x, -(poles @ np.cross(ecliptic_pole, x))))
    return -fit_harmonics(t_tdb_d, node, periodic or {}, degree=1).poly[1]


def free_nutation_amplitude(t, omega_body, moments):
    """Amplitude (rad) of the free (Euler) nutation, the angle between figure axis and L it adds.

    Least-squares fit of m = (w_x + i w_y)/w_z to a + b exp(i sigma_E t) with the
    Euler (Chandler, rigid) frequency sigma_E = w_z (C - A)/A in body axes
    (ch. 15; ~305 d for the Earth).  tan(angle) = (A/C)|m| for an axisymmetric top.
    Sample densely enough to resolve the forced nearly-diurnal terms (<= 0.25 d).
    """
    a, c = 0.5 * (moments[0] + moments[1]), moments[2]
    w_z = float(np.mean(omega_body[:, 2]))
    m = (omega_body[:, 0] + 1j * omega_body[:, 1]) / omega_body[:, 2]
    sigma = w_z * (c - a) / a
    design = np.column_stack([np.ones_like(t), np.exp(1j * sigma * (t - t[0]))])
    coef = np.linalg.lstsq(design, m, rcond=None)[0]
    return float(a / c * abs(coef[1]))


def node_and_inclination(poles, plane_frame):
    """(psi, I) rad, psi unwrapped: the equator of poles (n, 3) on a fixed plane whose frame ``plane_frame`` (3, 3,
    rows: the plane's x axis, y axis, pole) they are given against -- psi the equator's ascending node along the
    plane from its x axis, I the angle between the poles (pole = (sin I sin psi, -sin I cos psi, cos I))."""
    local = np.asarray(poles, dtype=float) @ np.asarray(plane_frame, dtype=float).T
    return np.unwrap(np.arctan2(local[:, 0], -local[:, 1])), np.arccos(np.clip(local[:, 2], -1.0, 1.0))


def axial_precession_rate(mean_motion, spin_rate, ellipticity, obliquity, eccentricity):
    """A rigid body's precession rate in longitude (rad per unit of the rates) under one mass on a fixed
    ellipse: -(3/2) (n^2 / w) H cos(eps) (1 - e^2)^(-3/2), H = (C - (A + B)/2)/C (Euler ch. 16 P96, §846, with
    the orbit's mean of a^3/r^3)."""
    return (-1.5 * mean_motion ** 2 / spin_rate * ellipticity * np.cos(obliquity)
            * (1.0 - eccentricity ** 2) ** -1.5)
