"""Mercury's spin against the radar and the altimeter (Margot et al. 2012; Stark et al. 2015), the forced
libration's closed form and Peale's equation; and the obliquity of runs whose orbit's node precession is scaled.

Edge module (astropy units); the scene (scenes/mercury_spin) declares, this measures.
"""
import math

import numpy as np

from ..analysis import cassini
from ..analysis import resonant_spin as rs
from ..bodies import mercury
from ..constants import ARCSEC
from ..plots import plot_series
from ..scene import Outcome

ARCMIN = 60 * ARCSEC


def measured(t, q, context):
    """{obliquity (settled, mean, free), libration fit, gamma (rad)} of a run's attitudes q at t, as its model's
    context (spinorbit.analysis.resonant_spin.cassini_system) gives the orbit."""
    orbit = context["orbit"]
    spin = rs.body_axes(q)[1]
    centre, free, mean_axis = cassini.settled_axis(t, spin, orbit.normal, orbit.normal_rate, orbit.t_ref,
                                                   context["alpha"])
    gamma = rs.libration(t, q, orbit)
    w0 = context["theory"]["w0_over_n"] * orbit.n
    return {"settled": cassini.angle(centre, orbit.normal), "mean": cassini.angle(mean_axis, orbit.normal),
            "free": free, "fit": rs.fit_libration(t, gamma, orbit, w0), "gamma": gamma}


def obliquity_series(t, q, orbit):
    """The spin axis's angle (rad) from the orbit normal moving as fitted, at each output."""
    spin = rs.body_axes(q)[1]
    moving = orbit.normal + np.outer(t - orbit.t_ref, orbit.normal_rate)
    cosine = np.einsum("ij,ij->i", spin, moving) / np.linalg.norm(moving, axis=1)
    return np.arccos(np.clip(cosine, -1.0, 1.0))


def metrics(m, context):
    """The summary's comparison of a measurement ``m`` (``measured``)."""
    theory, fit = context["theory"], m["fit"]
    amplitude = math.copysign(math.hypot(fit["amplitude_88d"], fit["cos_88d"]), fit["amplitude_88d"])
    return {
        "obliquity_arcmin": m["settled"] / ARCMIN,
        "obliquity_mean_arcmin": m["mean"] / ARCMIN,
        "obliquity_peale_arcmin": context["peale_obliquity"] / ARCMIN,
        "free_precession_arcsec": m["free"] / ARCSEC,
        "libration_amplitude_arcsec": amplitude / ARCSEC,
        "libration_phase_lag_deg": math.degrees(math.atan2(-fit["cos_88d"], fit["amplitude_88d"])),
        "libration_closed_form_arcsec": theory["amplitude_series"] / ARCSEC,
        "libration_linear_theory_arcsec": theory["amplitude_linear"] / ARCSEC,
        "free_libration_arcsec": None if fit["free"] is None else fit["free"] / ARCSEC,
        "libration_fit_residual_rms_arcsec": fit["residual_rms"] / ARCSEC,
        "orbit_normal_speed_arcsec_per_yr": float(np.linalg.norm(context["orbit"].normal_rate)) * 365.25 / ARCSEC,
        "free_precession_period_yr": 2 * math.pi / context["alpha"] / 365.25,
        "margot_2012_obliquity_arcmin": mercury.OBLIQUITY_ARCMIN[0],
        "margot_2012_libration_arcsec": mercury.LIBRATION_AMPLITUDE_ARCSEC[0],
        "stark_2015_obliquity_arcmin": mercury.STARK_2015["obliquity_arcmin"][0],
        "stark_2015_libration_arcsec": mercury.STARK_2015["libration_arcsec"][0],
    }


def precession_row(scale, m, context):
    """One row of the precession table: the node precession's scale, the normal's speed, Peale's and the settled
    obliquity."""
    return {"scale": scale,
            "orbit_normal_speed_arcsec_per_yr": float(np.linalg.norm(context["orbit"].normal_rate)) * 365.25 / ARCSEC,
            "obliquity_peale_arcmin": context["peale_obliquity"] / ARCMIN,
            "obliquity_arcmin": m["settled"] / ARCMIN, "free_precession_arcsec": m["free"] / ARCSEC}


def two_mercury_years(t, m, context):
    """(days from start, the run's libration less the fitted slow and free parts, the linear forced solution),
    arcsec, over two orbits."""
    orbit, g = context["orbit"], context["theory"]["g"]
    shown = t - t[0] <= 4 * math.pi / orbit.n
    anomaly = orbit.anomaly(t[shown])
    k = np.arange(1, g.size + 1)
    forced = np.sin(np.outer(anomaly, k)) @ g
    slow = m["gamma"][shown] - forced
    slow_fit = np.polyval(np.polyfit(t[shown] - t[0], slow, 2), t[shown] - t[0])
    return t[shown] - t[0], (m["gamma"][shown] - slow_fit) / ARCSEC, forced / ARCSEC


def outcome(t, q, context, rows):
    """The scene's Outcome: metrics, the table's columns, the figures, the precession table."""
    import astropy.units as u

    from .. import plots

    m = measured(t, q, context)
    comparison = metrics(m, context)
    if rows:
        comparison["precession_peale_error_max_arcsec"] = max(
            abs(r["obliquity_arcmin"] - r["obliquity_peale_arcmin"]) * 60 for r in rows)
    days, libration, forced = two_mercury_years(t, m, context)
    obliquity = obliquity_series(t, q, context["orbit"]) / ARCMIN
    year = 2000.0 + t / 365.25
    figures = {
        "libration": plot_series(days, [libration, forced], "days from the start",
                                 "libration in longitude [arcsec]",
                                 ["run (slow part removed)", "linear forced solution"]),
        "obliquity": plot_series(year, [obliquity, np.full_like(year, comparison["obliquity_arcmin"]),
                                        np.full_like(year, comparison["obliquity_peale_arcmin"]),
                                        np.full_like(year, mercury.OBLIQUITY_ARCMIN[0])],
                                 "year (TDB)", "obliquity [arcmin]",
                                 ["spin axis from the mean orbit normal", "settled (Cassini state)",
                                  "Peale's equation", "Margot et al. 2012"]),
    }
    if rows:
        scales = np.array([r["scale"] for r in rows])
        figures["obliquity_vs_precession"] = plots.plot_series(
            scales, [[r["obliquity_arcmin"] for r in rows], [r["obliquity_peale_arcmin"] for r in rows]],
            "node precession (x the orbit's own)", "obliquity [arcmin]", ["settled, integrated", "Peale's equation"])
    columns = {"obliquity": obliquity * u.arcmin, "libration": m["gamma"] / ARCSEC * u.arcsec}
    return Outcome(comparison, columns, figures, sections={"precession": rows})
