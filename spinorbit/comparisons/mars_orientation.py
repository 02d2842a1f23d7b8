"""Mars's orientation against its references: the precession rate against Konopliv et al. 2016's, the nutation
term by term against the rigid series Konopliv et al. 2006 adopt (references.mars_nutation), the pole against
IAU 2015's over 1980-2030 (references.mars_iau2015), and the rate's budget from runs with one effect added at
a time.

The pole's angles are taken on the mean orbit of J2000 (bodies.mars, Konopliv et al. 2006): psi the node of
Mars's equator along it from its node on the ICRF equator, I the obliquity; both fitted as a quadratic in T
with the series' frequencies (analysis.precession.fit_pole), the linear coefficient the rate at J2000.
"""
import math
from dataclasses import replace

import numpy as np

from ..analysis.precession import (
    RATE_MIN_SPAN_D,
    axial_precession_rate,
    fit_pole,
    mean_pole_offset,
    node_and_inclination,
    rate_refusal,
)
from ..base.constants import ARCSEC, JULIAN_YEAR_D, MAS
from ..bodies import mars
from ..orbits.sources import TwoBody
from ..references import mars_iau2015, mars_nutation
from ..scene.verdict import Check, Verdict
from ..starts import mars as start

NUTATION_MIN_SPAN_D = 10 * JULIAN_YEAR_D      # five Mars years: the annual term apart from the quadratic
IAU_WINDOW_D = (-20 * JULIAN_YEAR_D, 30 * JULIAN_YEAR_D)      # 1980-2030, where IAU 2015's fit is compared
# The metrics the verdict judges (the summary's comparison keys; the API's expected accuracy reads the pole's)
NUTATION_MINUS_RIGID_SERIES_MAX_MAS = "nutation_minus_rigid_series_max_mas"
POLE_MINUS_IAU2015_MAX_ARCSEC = "pole_minus_iau2015_max_arcsec"
RATE_MINUS_KONOPLIV2016_MAS_PER_YR = "rate_minus_konopliv2016_mas_per_yr"
# The budget's runs, each adding one effect to the last: name -> (the run's parameters, the last run's) -> its own.
def _solar(p, last):
    return replace(last, orbit=replace(last.orbit, source=TwoBody("kepler"), planets=False),
                   mars=replace(last.mars, satellites=False, geodesic_precession=False))


BUDGET = {"solar": _solar,
          "phobos_deimos": lambda p, last: replace(last, mars=replace(last.mars, satellites=True)),
          # the run's own ephemeris: the planets move the orbit
          "orbit_motion": lambda p, last: replace(last, orbit=replace(last.orbit, source=p.orbit.source)),
          "planet_torques": lambda p, last: replace(last, orbit=replace(last.orbit, planets=True)),
          "geodesic": lambda p, last: replace(last, mars=replace(last.mars, geodesic_precession=True))}


_RATE = ("Konopliv et al. 2016 (Icarus 274, 253): -7608.3 +- 2.1 mas/yr from landers and orbiters; the model "
         "predicts it from MRO120D's J2, the torques and C/MR^2 = 0.36367 +- 0.00010 (+-2.1 mas/yr), which Baland "
         "et al. 2020 (CMDA 132, 47) fitted to this rate with their rigid model: a check of these torques against "
         "theirs, not an independent measurement")
_NUTATION = ("the rigid series Konopliv et al. 2006 adopt (Reasenberg & King 1979), per frequency: its amplitudes "
             "scale with a precession constant it does not state (0.65 % under this moment's), its arguments put "
             "the Sun 0.036 deg behind DE421's (summary orbit_argument_lead_deg); Baland et al. 2020's BMAN20, for "
             "this moment, is the series a 1 mas check needs")
_IAU = ("IAU 2015 (Archinal et al. 2018) fits Opportunity's tracking (Kuchynka et al. 2014) over 1980-2030; "
        "its precession is a fitted circle (its rate: summary iau2015_rate_mas_per_yr)")


def verdict(p, comparison):
    """The rate (with every torque on), the nutation and the pole, each against its reference."""
    checks = [Check("nutation − rigid series", NUTATION_MINUS_RIGID_SERIES_MAX_MAS, 1.0, " mas", _NUTATION,
                    min_span_d=NUTATION_MIN_SPAN_D),
              Check("pole − IAU 2015 (1980–2030)", POLE_MINUS_IAU2015_MAX_ARCSEC, 0.3, "″", _IAU)]
    complete = p.mars.satellites and p.mars.geodesic_precession and p.orbit.planets
    if complete and not p.orbit.source.analytic:      # the orbit moved by the planets
        checks.insert(0, Check("ψ rate − Konopliv 2016", RATE_MINUS_KONOPLIV2016_MAS_PER_YR, 5.0,
                               " mas/yr", _RATE, min_span_d=RATE_MIN_SPAN_D))
    return Verdict("Konopliv et al. 2016 (moment: Baland et al. 2020), rigid nutation, IAU 2015", tuple(checks))


def outcome(p, run):
    """The scene's Outcome: the comparisons, the budget (comparison.budget), the table and the figures."""
    from ..scene.declaration import Outcome

    t, system, y = run.times, run.model.system, run.solution.y
    poles = system.figure_axes("mars", t, y)
    comparison, not_measured, columns = precession_nutation(t, poles)
    iau, iau_not_measured, separation = against_iau(t, poles)
    comparison.update(iau)
    comparison.update(argument_leads(t, system.motion.externals, comparison))
    not_measured.update(iau_not_measured)
    if p.comparison.budget and comparison.get("precession_rate_mas_per_yr") is not None:
        comparison.update(budget(p, run, t))
    w = prime_meridian_of(system, t, y, poles, system.t0)
    return Outcome(comparison, figures=figures(t, poles, columns, separation), not_measured=not_measured,
                   table=table(t, poles, w, columns, separation),
                   sections={"reference": provenance(), "model": model_summary(system)})


def angles(poles):
    """(psi, I) rad of poles (n, 3) on the J2000 mean orbit."""
    return node_and_inclination(poles, start.mean_orbit_frame())


def rate_mas_yr(fit):
    """The fit's linear coefficient (rad per century) in mas/yr."""
    return fit.poly[1] / MAS / 100.0


def fitted(t, poles):
    """(psi fit, I fit, psi, I) of poles at TDB days t (analysis.precession.fit_pole on the series' frequencies)."""
    psi, inc = angles(poles)
    fit_psi, fit_inc = fit_pole(t, psi, inc, mars_nutation.arguments(t))
    return fit_psi, fit_inc, psi, inc


def precession_nutation(t, poles):
    """(comparison, not_measured, columns): the rates, the nutation against the rigid series (over a span of
    NUTATION_MIN_SPAN_D or more), the angles."""
    fit_psi, fit_inc, psi, inc = fitted(t, poles)
    comparison, not_measured = {}, {}
    if why := rate_refusal(float(np.ptp(t))):
        for key in ("precession_rate_mas_per_yr", "obliquity_rate_mas_per_yr", RATE_MINUS_KONOPLIV2016_MAS_PER_YR):
            comparison[key], not_measured[f"comparison.{key}"] = None, why
    else:
        rate = rate_mas_yr(fit_psi)
        comparison.update({"precession_rate_mas_per_yr": rate, "obliquity_rate_mas_per_yr": rate_mas_yr(fit_inc),
                           RATE_MINUS_KONOPLIV2016_MAS_PER_YR: rate - mars.PRECESSION_RATE_MAS_YR[0]})
    residuals = []
    for name, reference in mars_nutation.by_frequency().items():
        if fit_psi.sin[name] is None:
            not_measured[f"comparison.nutation_{name}"] = fit_psi.refused[name]
            continue
        model = (fit_psi.sin[name], fit_psi.cos[name], fit_inc.cos[name], fit_inc.sin[name])
        for part, value, ref in zip(("dpsi_sin", "dpsi_cos", "deps_cos", "deps_sin"), model, reference):
            comparison[f"nutation_{name}_{part}_mas"] = value / MAS
            residuals.append((value - ref) / MAS)
    comparison[NUTATION_MINUS_RIGID_SERIES_MAX_MAS] = max(map(abs, residuals)) if residuals else None
    if float(np.ptp(t)) < NUTATION_MIN_SPAN_D:
        comparison = {k: v for k, v in comparison.items() if not k.startswith("nutation_")}
        comparison[NUTATION_MINUS_RIGID_SERIES_MAX_MAS] = None
        not_measured[f"comparison.{NUTATION_MINUS_RIGID_SERIES_MAX_MAS}"] = (
            f"the nutation's terms need a span of {NUTATION_MIN_SPAN_D:.0f} d, the run has {float(np.ptp(t)):.0f} d")
    mean_psi, mean_inc = mean_pole_offset(t, fit_psi), mean_pole_offset(t, fit_inc)
    columns = {"precession_psi": (psi, "rad"), "obliquity": (inc, "rad"), "nutation_psi": (psi - mean_psi, "rad"),
               "nutation_obliquity": (inc - mean_inc, "rad")}
    return comparison, not_measured, columns


def argument_leads(t, externals, comparison):
    """{"orbit_argument_lead_deg", "nutation_2M_lead_deg"}: how far the run's Sun leads the series' arguments in
    mean longitude from Mars's mean equinox (:func:`solar_longitude_lead`), and how far the model's 2M nutation
    term leads the series' in phase (about twice the former: the 2M + q term, 25 times the 2M one, goes as 2
    lambda); empty when the span is too short for the nutation."""
    if comparison.get("nutation_2M_dpsi_sin_mas") is None or "sun" not in externals.names:
        return {}
    sun = externals.positions(t)[:, externals.names.index("sun")]
    series = mars_nutation.by_frequency()["2M"]
    model = complex(comparison["nutation_2M_dpsi_sin_mas"], comparison["nutation_2M_dpsi_cos_mas"])
    lead = math.degrees(np.angle(model / complex(series[0], series[1])))
    return {"orbit_argument_lead_deg": solar_longitude_lead(t, sun), "nutation_2M_lead_deg": lead}


def solar_longitude_lead(t, sun):
    """The Sun's mean longitude seen from Mars (``sun``: (n, 3) km, ICRF, at TDB days t), counted along the J2000
    mean orbit from Mars's equinox (the node of IAU 2015's pole's equator), minus the series' M + q/2, deg at
    J2000: the difference fitted as a constant, a drift and the equation of centre's harmonics of M, modulo 180
    deg (the nutation sees 2 lambda)."""
    local = sun @ start.mean_orbit_frame().T
    psi = angles(mars_iau2015.pole(t))[0]
    series = mars_nutation.mean_anomaly(t) + 0.5 * math.radians(mars_nutation.Q_DEG)
    gap = np.unwrap(np.arctan2(local[:, 1], local[:, 0]) - psi - series)
    m = mars_nutation.mean_anomaly(t)
    design = np.column_stack([np.ones_like(t), t / JULIAN_YEAR_D]
                             + [f(k * m) for k in range(1, 5) for f in (np.sin, np.cos)])
    lead = math.degrees(np.linalg.lstsq(design, gap, rcond=None)[0][0])
    return (lead + 90.0) % 180.0 - 90.0


def against_iau(t, poles):
    """(comparison, not_measured, separation rad (n,) or None): the pole against IAU 2015's over 1980-2030 and
    IAU 2015's own rate fitted alike over the run."""
    iau = mars_iau2015.pole(t)
    inside = (t >= IAU_WINDOW_D[0]) & (t <= IAU_WINDOW_D[1])
    separation = _angle(poles, iau)
    comparison, not_measured = {}, {}
    if inside.any():
        comparison[POLE_MINUS_IAU2015_MAX_ARCSEC] = float(separation[inside].max() / ARCSEC)
    else:
        comparison[POLE_MINUS_IAU2015_MAX_ARCSEC] = None
        not_measured[f"comparison.{POLE_MINUS_IAU2015_MAX_ARCSEC}"] = "the run does not reach 1980-2030"
    if rate_refusal(float(np.ptp(t))) is None:
        comparison["iau2015_rate_mas_per_yr"] = rate_mas_yr(fitted(t, iau)[0])
    return comparison, not_measured, separation


def _angle(a, b):
    """Angles (rad) between unit vectors (n, 3), accurate when small."""
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=1), np.sum(a * b, axis=1))


def prime_meridian(t, poles, spin_rate, t0):
    """W (rad) of an axisymmetric Mars whose pole moves along ``poles`` and spins at w_z = ``spin_rate`` about its
    figure axis, W(t0) = IAU 2015's: the 3-1-3 kinematics w_z = dW/dt + sin(delta) d alpha/dt integrated
    (trapezoids on the output grid)."""
    ra, dec = np.unwrap(np.arctan2(poles[:, 1], poles[:, 0])), np.arcsin(np.clip(poles[:, 2], -1.0, 1.0))
    turned = np.concatenate([[0.0], np.cumsum(0.5 * (np.sin(dec[1:]) + np.sin(dec[:-1])) * np.diff(ra))])
    w0 = mars_iau2015.angles([t0])[2][0]
    return w0 + spin_rate * (t - t0) - (turned - np.interp(t0, t, turned))


def budget(p, run, t):
    """(comparison, runs' rates): each effect's share of the rate, mas/yr, from runs adding one at a time
    (BUDGET), beside the closed forms of the solar and geodesic rows."""
    rates, variant, last = {}, p, None
    for name, change in BUDGET.items():
        variant = change(p, variant)
        system = start.build(variant)
        states, _ = run.integrate(system, t, f"budget: {name}", estimate_error=False)
        rate = rate_mas_yr(fitted(t, system.figure_axes("mars", t, states.y))[0])
        rates[name] = rate - (last if last is not None else 0.0)
        last = rate
    comparison = {f"budget_{name}_mas_per_yr": value for name, value in rates.items()}
    comparison["budget_planets_mas_per_yr"] = rates["orbit_motion"] + rates["planet_torques"]
    comparison["budget_total_mas_per_yr"] = last
    comparison.update(closed_forms(p.mars.c_mr2))
    return comparison


def closed_forms(c_mr2):
    """The solar row's closed form (the mean ellipse, the J2000 obliquity, H = J2 / ``c_mr2``) and de Sitter's rate,
    mas/yr."""
    n = math.radians(mars.MEAN_MOTION_DEG_D)
    obliquity = angles(mars_iau2015.pole([0.0]))[1][0]
    solar = axial_precession_rate(n, mars.ROTATION_RATE_RAD_D, mars.J2 / c_mr2, obliquity,
                                  mars.MEAN_ECCENTRICITY)
    geodesic = float(np.linalg.norm(start.geodesic()[0]))
    return {"closed_form_solar_mas_per_yr": solar * JULIAN_YEAR_D / MAS,
            "closed_form_geodesic_mas_per_yr": geodesic * JULIAN_YEAR_D / MAS}


def prime_meridian_of(system, t, states, poles, t0):
    """W (rad, continuous) of the run: from the spin for a gyroscopic Mars (:func:`prime_meridian`), from the
    attitude otherwise (the prime meridian bodies.mars.A_AXIS_LONGITUDE_DEG west of the body x axis, measured
    from the equator's node on the ICRF equator)."""
    from ..base.rotations import matrices_from_quats

    if "mars.spin" in system.layout:
        spin = system.state(states, "mars.spin")
        rate = float(np.linalg.norm(spin[0]) / system.bodies["mars"].figure.moments[2])
        return prime_meridian(t, poles, rate, t0)
    lon = math.radians(mars.A_AXIS_LONGITUDE_DEG)
    meridian = matrices_from_quats(system.state(states, "mars.q")) @ np.array([math.cos(lon), -math.sin(lon), 0.0])
    node = np.cross([0.0, 0.0, 1.0], poles)
    node /= np.linalg.norm(node, axis=1)[:, None]
    return np.unwrap(np.arctan2(np.sum(np.cross(node, meridian) * poles, axis=1), np.sum(node * meridian, axis=1)))


COLUMNS = {
    "pole_ra": ("deg", "right ascension of the model's figure axis (Mars's pole), ICRF"),
    "pole_dec": ("deg", "declination of the model's figure axis (Mars's pole), ICRF"),
    "prime_meridian": ("deg", "W: the prime meridian's angle along Mars's equator from its node on the ICRF "
                              "equator (IAU convention; continuous)"),
    "mars_precession_longitude": ("arcsec", "psi of the model's mean pole: the node of Mars's mean equator on the "
                                            "J2000 mean orbit, from that orbit's node on the ICRF equator"),
    "mars_obliquity": ("deg", "the model's obliquity I to the J2000 mean orbit (nutation included)"),
    "mars_nutation_longitude": ("mas", "the nutation in longitude: psi minus its fitted quadratic"),
    "mars_nutation_obliquity": ("mas", "the nutation in obliquity: I minus its fitted quadratic"),
    "pole_minus_iau2015": ("arcsec", "angle between the model's pole and IAU 2015's (Archinal et al. 2018)"),
}


def table(t, poles, w, columns, separation):
    """The run's table (COLUMNS)."""
    from ..scene.columns import quantity_table

    ra, dec = np.arctan2(poles[:, 1], poles[:, 0]) % (2 * math.pi), np.arcsin(np.clip(poles[:, 2], -1.0, 1.0))
    values = {"pole_ra": np.degrees(ra), "pole_dec": np.degrees(dec), "prime_meridian": np.degrees(w),
              "mars_precession_longitude": (columns["precession_psi"][0] - columns["nutation_psi"][0]) / ARCSEC,
              "mars_obliquity": np.degrees(columns["obliquity"][0]),
              "mars_nutation_longitude": columns["nutation_psi"][0] / MAS,
              "mars_nutation_obliquity": columns["nutation_obliquity"][0] / MAS,
              "pole_minus_iau2015": separation / ARCSEC}
    return quantity_table(t, values, COLUMNS)


def answer_table(t, poles, w):
    """The API's table (spinorbit.orientation): the pole, W in [0, 360) deg and the angle from IAU 2015's pole."""
    from ..scene.columns import quantity_table

    separation = _angle(poles, mars_iau2015.pole(t))
    ra, dec = np.arctan2(poles[:, 1], poles[:, 0]) % (2 * math.pi), np.arcsin(np.clip(poles[:, 2], -1.0, 1.0))
    values = {"pole_ra": np.degrees(ra), "pole_dec": np.degrees(dec), "prime_meridian": np.degrees(w) % 360.0,
              "pole_minus_iau2015": separation / ARCSEC}
    columns = {**COLUMNS, "prime_meridian": ("deg", COLUMNS["prime_meridian"][1].replace("continuous", "0-360"))}
    return quantity_table(t, values, {name: columns[name] for name in values})


def figures(t, poles, columns, separation):
    """The pole beside IAU 2015's, and the nutation beside the rigid series."""
    from ..plots.common import plot_panels

    years = 2000.0 + t / JULIAN_YEAR_D
    iau = mars_iau2015.pole(t)
    ra = [np.degrees(np.unwrap(np.arctan2(p[:, 1], p[:, 0]))) % 360.0 for p in (poles, iau)]
    dec = [np.degrees(np.arcsin(p[:, 2])) for p in (poles, iau)]
    series = mars_nutation.nutation(t)
    return {"pole_vs_iau2015": plot_panels(years, [
                (ra, ["model", "IAU 2015"], "pole RA (deg)"), (dec, ["model", "IAU 2015"], "pole Dec (deg)"),
                ([separation / ARCSEC], ["model − IAU 2015"], "separation (″)")], "year"),
            "nutation": plot_panels(years, [
                ([columns["nutation_psi"][0] / MAS, series[0] / MAS], ["model", "rigid series"], "Δψ (mas)"),
                ([columns["nutation_obliquity"][0] / MAS, series[1] / MAS], ["model", "rigid series"],
                 "ΔI (mas)"),
                ([(columns["nutation_psi"][0] - series[0]) / MAS, (columns["nutation_obliquity"][0] - series[1]) / MAS],
                 ["Δψ", "ΔI"], "model − series (mas)")], "year")}


def provenance():
    return {"rate": "Konopliv et al. 2016, Icarus 274, 253",
            "moment": "Baland et al. 2020, CMDA 132, 47 (C/MR^2 = 0.36367 +- 0.00010 from Konopliv et al. 2016's rate)",
            "nutation": mars_nutation.CITATION,
            "pole": mars_iau2015.CITATION}


def model_summary(system):
    """What acts on Mars in this run."""
    return {"interactions": [type(i).__name__ for i in system.interactions],
            "bodies_seen": list(system.motion.externals.names), "orbit_source": system.motion.externals.source
            if hasattr(system.motion.externals, "source") else "kepler",
            "dynamical_ellipticity": float(1.0 - np.mean(system.bodies["mars"].figure.moments[:2])
                                           / system.bodies["mars"].figure.moments[2])}
