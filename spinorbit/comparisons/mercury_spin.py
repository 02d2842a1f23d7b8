"""Mercury in its 3:2 spin-orbit resonance on an N-body orbit: the Cassini-state obliquity and the 88-day
forced libration, against the radar (Margot et al. 2012, JGR 117, E00L09) and the altimeter (Stark et al.
2015).

Mercury turns under the Sun's torque on its degree-2 figure (Euler ch. 16 P91, §815) as a mantle over a
fluid core (spinorbit.models.rotators.MantleCore; J2, C22, C/(M R^2) = 0.346 and C_m/C = 0.431 from
spinorbit.bodies.mercury), on DE421's orbit (or REBOUND's), whose node and perihelion precess under the
planets.  The core is pulled to the mantle's rotation by friction in ``core.coupling_time`` (1 yr): long
against the 88 days, so the mantle librates alone ((B - A)/C_m), short against the precession, so the whole
planet (C) precesses -- the assumption under which Margot et al. read C from the obliquity and C_m from the
libration.  It lags the spin axis by |dk/dt| tau (0.6" at 1 yr) and delays the libration by (C_c/C_m)/(n
tau) (3 deg).

The start (analysis/resonant_spin): the spin axis in Peale's Cassini state for the orbit normal's mean speed
over the run (analysis/cassini), the long axis on the forced libration.  The obliquity reported is the state
the spin settles to: the spin circles it at the free precession (~1300 yr), and from its velocity over the
run the centre is found (``cassini.settled_axis``; ``start.obliquity_offset`` starts it away to show that
the centre does not depend on the start).  The libration is the sin M term fitted with M's harmonics, a
quadratic and the free libration.  Further runs with the orbit's node precession scaled
(``precession.scales``: the orbit turned about k x dk/dt, orbits.interpolant.turned) show the obliquity
follows Peale's equation (Baland et al. 2017).  The Cassini state is that of the normal's secular motion: the
normal's periodic terms (years to decades) bias a decade's mean speed by a few percent, so the scene runs a
century (benchmarks/RESULTS.md, Mercury).

Edge module (astropy units); the scene (scenes/mercury_spin) declares, spinorbit.starts.mercury starts it, this
measures and judges.
"""
import math

import numpy as np

from ..analysis import cassini
from ..analysis import resonant_spin as rs
from ..base.constants import ARCSEC
from ..bodies import mercury
from ..plots.common import plot_series
from ..scene.declaration import Outcome
from ..scene.verdict import Check, Verdict

ARCMIN = 60 * ARCSEC


def measured(t, q, context):
    """{obliquity (settled, mean, free), libration fit, gamma (rad)} of a run's attitudes q at t, as its model's
    context (spinorbit.analysis.resonant_spin.cassini_system) gives the orbit."""
    orbit = context["orbit"]
    spin = rs.body_axes(q)[1]
    centre, free, mean_axis = cassini.settled_axis(t, spin, orbit.normal, orbit.normal_rate, orbit.t_ref,
                                                   context["alpha"], context["inclination"])
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
        figures["obliquity_vs_precession"] = plot_series(
            scales, [[r["obliquity_arcmin"] for r in rows], [r["obliquity_peale_arcmin"] for r in rows]],
            "node precession (x the orbit's own)", "obliquity [arcmin]", ["settled, integrated", "Peale's equation"])
    columns = {"spin_obliquity": obliquity * u.arcmin, "libration": m["gamma"] / ARCSEC * u.arcsec}
    return Outcome(comparison, columns, figures, sections={"precession": rows})


MARGOT, STARK = "Margot et al. 2012 radar (1 sigma)", "Stark et al. 2015 laser altimetry (1 sigma)"
PEALE_TOLERANCE_ARCMIN = 0.05
PEALE_WHY = ("3\": the core's lag |dk/dt| tau (0.6\"), the orbit normal's periodic wobbles over the run "
             "(~1\" on DE421) and the pericentre's precession (0.1 % of eps, Baland et al. 2017), which "
             "Peale's equation omits")
CLOSED_FORM_WHY = ("1 %: the e^6 remainder (0.13 %), the core's friction (0.1-0.5 %) and the planets' "
                   "perturbations of the orbit, which the closed form omits")


def observed(label, metric, measured, unit, source):
    """A check of ``metric`` within a published (value, sigma)."""
    return Check(label, metric, measured[1], unit, source, expected=measured[0])


def verdict(p, comparison):
    """The obliquity and the libration within the radar's and the altimeter's 1 sigma; the libration against
    the closed form; the obliquity against Peale's equation (and, with scaled precession, every run's)."""
    oblique, libration = "obliquity_arcmin", "libration_amplitude_arcsec"
    checks = [observed("obliquity (radar)", oblique, mercury.OBLIQUITY_ARCMIN, "′", MARGOT),
              observed("libration (radar)", libration, mercury.LIBRATION_AMPLITUDE_ARCSEC, "″", MARGOT),
              observed("obliquity (altimetry)", oblique, mercury.STARK_2015["obliquity_arcmin"], "′", STARK),
              observed("libration (altimetry)", libration, mercury.STARK_2015["libration_arcsec"], "″", STARK),
              Check("libration vs (3/2)(B-A)/C_m (1 - 11e^2 + 959e^4/48)", libration, 0.01, "",
                    CLOSED_FORM_WHY, versus="libration_closed_form_arcsec", relative=True),
              Check("obliquity vs Peale's equation", oblique, PEALE_TOLERANCE_ARCMIN, "′", PEALE_WHY,
                    versus="obliquity_peale_arcmin")]
    if p.precession.scales:
        checks.append(Check("scaled precession vs Peale's equation", "precession_peale_error_max_arcsec",
                            60 * PEALE_TOLERANCE_ARCMIN, "″", PEALE_WHY))
    return Verdict("Margot et al. 2012; Stark et al. 2015; closed forms", tuple(checks),
                   "C/MR^2 and C_m/C were inferred from these observations with this theory: agreement "
                   "checks that the integrated spin realises it on an N-body orbit, not the interior")


def compare(p, run):
    """The scene's comparison: the main run measured, and one run per precession scale."""
    from ..starts.mercury import model, scales

    rows = []
    for scale in scales(p):
        system, context = model(p, run.times, scale)
        solution, _ = run.integrate(system, run.times, f"precession x{scale:g}")
        rows.append(precession_row(scale, measured(solution.t, solution.quaternion, context), context))
    return outcome(run.solution.t, run.solution.quaternion, run.model.context, rows)
