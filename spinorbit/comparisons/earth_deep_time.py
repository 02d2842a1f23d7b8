"""earth_deep_time's comparisons: ERFA's long-term precession over the first 2 kyr, La2004 over 1 Myr, 10 Myr
and the span (up to the solar system's chaos), La93's tidal variants beside it."""
import math

import numpy as np

from ..base.constants import ARCSEC, JULIAN_YEAR_D
from ..starts.earth_deep_time import ERFA_SPAN_D, KYR_D, MYR_D

WINDOWS_MYR = (1, 10)                 # the spans the issue sets targets over
CHAOS_MYR = 50.0                      # La2004: "age calibrations of paleoclimatic data over 40 to 50 Myr"
ERFA_STEP_D = 10 * JULIAN_YEAR_D
# The metrics erfa_metrics computes (the summary's comparison keys, read by the verdict)
ERFA_OBLIQUITY_MAX_ARCSEC, ERFA_EQUATOR_MAX_ARCSEC = "erfa_obliquity_max_arcsec", "erfa_equator_max_arcsec"
# The differences of two solutions over a window (_differences); a window's metric is window_metric's name
ECCENTRICITY_MAX, OBLIQUITY_MAX_DEG = "eccentricity_max", "obliquity_max_deg"
CLIMATIC_PRECESSION_VECTOR_MAX, PERIHELION_LONGITUDE_END_DEG = ("climatic_precession_vector_max",
                                                                "perihelion_longitude_end_deg")
DIFFERENCES = (ECCENTRICITY_MAX, OBLIQUITY_MAX_DEG, CLIMATIC_PRECESSION_VECTOR_MAX, PERIHELION_LONGITUDE_END_DEG)
SPAN = "span"                         # the window of the whole span compared


def window_name(myr):
    """The name of the window of the first ``myr`` Myr ("1myr")."""
    return f"{myr}myr"


def window_metric(prefix, difference, window):
    """The summary's key of ``difference`` (one of DIFFERENCES) between the solutions ``prefix`` names
    ("la2004": the model minus La2004) over ``window`` (window_name's, or SPAN)."""
    return f"{prefix}_{difference}_{window}"


def la2004_metric(difference, window):
    """The summary's key of the model minus La2004's ``difference`` over ``window``, read by the verdicts."""
    return window_metric("la2004", difference, window)


def la2004_checks(span_length_d, targets, source):
    """The verdict's checks of the model minus La2004, one per ``targets``' (window in Myr, what, difference,
    tolerance, unit) whose window a span of ``span_length_d`` days covers (a shorter span's is not asked)."""
    from ..scene.verdict import Check

    checks = []
    for myr, what, difference, tolerance, unit in targets:
        window_d = myr * MYR_D
        if span_length_d >= window_d - 1.0:
            checks.append(Check(f"{what} vs La2004 ({window_name(myr)})", la2004_metric(difference, window_name(myr)),
                                tolerance, unit, source, min_span_d=window_d - 1.0))
    return checks


def erfa_metrics(p, model):
    """Obliquity and mean equator against ERFA's long-term precession over the span's first 2 kyr (arcsec)."""
    from ..integrators import simulate
    from ..references.long_term_precession import LongTermPrecession

    reach = min(ERFA_SPAN_D, abs(p.span.end))
    t = math.copysign(1.0, p.span.end) * np.arange(ERFA_STEP_D, reach + 1.0, ERFA_STEP_D)
    solution, _ = simulate(model.system, t, "rk8", {"step": ERFA_STEP_D}, estimate_error=False)
    states = solution.y
    normal, _ = model.system.orbit(t)
    reference = LongTermPrecession()(t)
    obliquity = np.arccos(np.clip(np.sum(states[:, :3] * normal, axis=1), -1, 1))
    equator = np.arccos(np.clip(np.sum(states[:, :3] * reference["equator_pole"], axis=1), -1, 1))
    obliquity_error = np.abs(obliquity - reference["obliquity_rad"]).max()
    return ({ERFA_OBLIQUITY_MAX_ARCSEC: float(obliquity_error / ARCSEC),
             ERFA_EQUATOR_MAX_ARCSEC: float(equator.max() / ARCSEC),
             "erfa_compared_kyr": float(reach / KYR_D)}, reference.provenance)


def laskar_metrics(t, q):
    """Against La2004 over each window and the span up to CHAOS_MYR, with La93's tidal variants' spread beside
    it where La93 reaches: (metrics, not_measured, provenance, La2004's series at t or None)."""
    from ..references import laskar

    reason = laskar.available()
    kyr = t / KYR_D
    if reason is None and not np.allclose(kyr, np.round(kyr), rtol=0, atol=1e-6):
        reason = "outputs off La2004's whole-kyr grid: give span.step a whole number of kyr"
    reach = min(abs(kyr[-1]), CHAOS_MYR * 1000)
    windows = [*((window_name(m), m * 1000.0) for m in WINDOWS_MYR if reach >= m * 1000), (SPAN, reach)]
    if reason is not None:
        keys = [la2004_metric(name, w) for w, _ in windows for name in DIFFERENCES]
        return dict.fromkeys(keys), {f"comparison.{k}": f"not compared: {reason}" for k in keys}, None, None
    inside = np.abs(kyr) <= reach + 1e-9
    solutions = {"model": {"eccentricity": q["eccentricity"][inside], "obliquity_rad": q["obliquity"][inside],
                           "perihelion_longitude_rad": q["perihelion_longitude"][inside]}}
    for name in ("La2004", "La93_01", "La93_11"):
        low, high = laskar.Insolation(name).span_kyr()
        covered = inside & (kyr >= low) & (kyr <= high)
        solutions[name] = laskar.Insolation(name)(t[covered]).values if covered.any() else None
    metrics = {}
    for prefix, a, b in (("la2004", "model", "La2004"), ("la93_tides", "La93_11", "La93_01"),
                         ("la2004_minus_la93", "La2004", "La93_11")):
        for window, limit in windows:
            size = int(np.sum(np.abs(kyr[inside]) <= limit + 1e-9))
            if solutions[a] is not None and solutions[b] is not None and min(
                    len(solutions[a]["eccentricity"]), len(solutions[b]["eccentricity"])) >= size:
                metrics.update({window_metric(prefix, k, window): v for k, v in
                                _differences(solutions[a], solutions[b], slice(0, size)).items()})
    not_measured = {}
    if abs(kyr[-1]) > reach:
        not_measured["comparison.la2004_span"] = (
            f"compared to {reach / 1000:g} Myr only: beyond, the solar system's chaos leaves any solution "
            "uncertain (La2004: 40 to 50 Myr)")
    la2004 = solutions["La2004"]
    reference = {"t_kyr": kyr[inside], "obliquity_deg": np.degrees(la2004["obliquity_rad"]),
                 "climatic_precession": la2004["eccentricity"] * np.sin(la2004["perihelion_longitude_rad"]),
                 "eccentricity": la2004["eccentricity"]}
    return metrics, not_measured, laskar.Insolation("La2004").provenance(), reference


EXPLAINED = {
    "la2004_*": "the model minus La2004 (Laskar et al. 2004) over the window: e, obliquity, the "
                "climatic-precession vector e(cos ϖ̄, sin ϖ̄) (max), ϖ̄ at the window's end",
    "la93_tides_*": "La93 with tides (La93_11) minus La93 without (La93_01), the same differences: how far "
                    "Laskar's own solution moves with its tidal model, the scale a tidal law sets on "
                    "agreement",
    "la2004_minus_la93_*": "La2004 minus La93 (with tides): how far two of Laskar's solutions differ"}


def sections(model, erfa_provenance, la2004_provenance):
    """The summary's model, orbital solution and reference sections of the scene's ``model`` (its spin, orbit
    and orbit_wall)."""
    orbit = model.orbit
    return {"model": model.spin.description,
            "orbital_solution": {"file": str(orbit.path), "span_d": list(orbit.span), "settings": orbit.record,
                                 **orbit.provenance, "wall_s_this_run": model.orbit_wall},
            "reference": {"erfa": erfa_provenance, "la2004": la2004_provenance}, "metrics_explained": EXPLAINED}


def figure_series(q, la2004):
    """(kyr, the model's obliquity (deg) and climatic precession, La2004's or None), where La2004 reaches."""
    size = len(q["t_kyr"]) if la2004 is None else len(la2004["t_kyr"])
    ours = {"obliquity_deg": np.degrees(q["obliquity"][:size]),
            "climatic_precession": q["climatic_precession"][:size], "eccentricity": q["eccentricity"][:size]}
    reference = None if la2004 is None else {k: v for k, v in la2004.items() if k != "t_kyr"}
    return q["t_kyr"][:size], ours, reference


def _differences(a, b, part):
    """Max differences of two solutions' values over ``part``: e, obliquity (deg), e exp(i varpi_bar); the
    varpi_bar difference at the window's end (deg)."""
    def vector(x):
        return x["eccentricity"][part] * np.exp(1j * x["perihelion_longitude_rad"][part])

    end = np.angle(vector(a)[-1] / vector(b)[-1])
    return {ECCENTRICITY_MAX: float(np.abs(a["eccentricity"][part] - b["eccentricity"][part]).max()),
            OBLIQUITY_MAX_DEG: float(np.degrees(np.abs(a["obliquity_rad"][part] - b["obliquity_rad"][part]).max())),
            CLIMATIC_PRECESSION_VECTOR_MAX: float(np.abs(vector(a) - vector(b)).max()),
            PERIHELION_LONGITUDE_END_DEG: float(np.degrees(end))}
