"""The Earth's dynamical ellipticity H_d: IAU 2006's, or the one that gives the observed precession rate.

The dynamical ellipticity is not measured: every theory infers it from the observed precession rate.  IAU
2006 (P03: Capitaine, Wallace & Chapront 2003, A&A 412, 567, Tables 3 and 4) took VLBI's rate in longitude,
psi_1 = 5038.481507"/cy at J2000, removed the theoretical contributions it does not scale (second order,
planets, J4, tides, nonlinear, geodesic) and divided the rest by Williams' (1994) first-order constant per
unit H.  ``earth.hd = "observed_rate"`` does the same with this model's own torque: a gyroscopic run with
IAU 2006's H_0 over 1950-2050 (centred on J2000, so the fitted rate is the rate at J2000 and not biased by the
t^2 term) on the scene's orbits and settings gives the model's rate and its rows,

    psi_1 = x F + x^2 S + G + N + T,    x = H_d / H_0,

F the rows that go as H (the first-order luni-solar torque with the tilts, the planets' direct torques, the
torques on J4, which are in fact independent of H but at 2.6 mas/cy move H by < 1e-12 if scaled), S the
second order (the nutation's feedback, as H^2), G the geodesic precession and N MHB2000's nonlinear rate
(a row of the observed rate, as in P03, which the non-rigid layer adds: H_d is the Earth's, the same with the
layer off) and T the tides' (``earth.tides``, earth_tides; independent of H); H_d is the root.  The obliquity
rate's rows come from the same run (with the tides'): it is not fitted, and is what is judged with the
nutation.

Edge module (ERFA through references.erfa_pole); the run is cached in memory per setting.
"""
import functools
import math

import numpy as np

from ..base.constants import ARCSEC, JULIAN_CENTURY_D, JULIAN_YEAR_D
from ..base.progress import stage
from ..bodies import earth
from ..references import arguments, erfa_pole

HALF_SPAN_D = 50 * JULIAN_YEAR_D         # the run: J2000 +- 50 yr
STEP_D = 2.0                             # rk8 step and output step (converged: RESULTS.md)
CHOICES = ("iau2006", "observed_rate")
# P03's omega_1, the obliquity rate on the J2000 ecliptic at J2000 (Table 4): the IAU 2006 ecliptic is the
# model's, so the model's rate is omega_1 + (model - IAU), both fitted alike.
P03_OBLIQUITY_RATE_ARCSEC_CY = -0.02575


def settings(p):
    """The keys the observed-rate H_d depends on, as a hashable tuple (the cache's key)."""
    return (p.orbit.source, p.orbit.planets, p.orbit.sample_step,
            p.earth.j2_rate, p.earth.j4, p.earth.geodesic_precession,
            p.earth.geodesic_nutation, p.earth.tides)


def dynamical_ellipticity(p):
    """(H_d, budget or None): the p's ``earth.dynamical_ellipticity`` (IAU 2006's by default) with
    ``earth.hd = "iau2006"``, else from_observed_rate(...) of its settings."""
    if p.earth.hd == "iau2006":
        return p.earth.dynamical_ellipticity, None
    budget = from_observed_rate(*settings(p))
    return budget["h_d"], budget


def summary(p):
    """The summary's "dynamical_ellipticity": the H_d the run took and where from (with its budget)."""
    h_d, budget = dynamical_ellipticity(p)
    return budget or {"h_d": h_d, "from": "earth.dynamical_ellipticity (IAU 2006's, P03 Table 4, by default)"}


@functools.lru_cache(maxsize=4)
def from_observed_rate(source, planets, sample_step, j2_rate, j4, geodesic, geodesic_nutation, tidal="none"):
    """The H_d that gives the model IAU 2006's rate in longitude at J2000, and the model's budget in
    longitude and obliquity at H_0 (the rows, "/cy, by the run's torques; see the module docstring)."""
    from ..integrators import simulate
    from ..models.assemblies.earth import rigid_earth
    from .earth_pole import PLANETS, ecliptic_pole, ren2000_scaled, started

    t = np.arange(-HALF_SPAN_D, HALF_SPAN_D + STEP_D / 2, STEP_D)
    bodies = ("moon", "sun") + (PLANETS if planets else ())
    orbits = source.relative("earth", bodies, t[0] - 1.0, t[-1] + 1.0, sample_step)
    system = rigid_earth(orbits, "gyroscopic", earth.H_D, 0.0, j2_rate, j4,
                         ecliptic_pole(None) if geodesic else None, geodesic and geodesic_nutation, t[0])
    # started on the IAU mean pole plus REN-2000's rigid nutation (x H_0 / H_REN), as the rigid run goes
    start = erfa_pole.from_mean_pole(t[:1], *ren2000_scaled(t[:1], earth.H_D, geodesic and geodesic_nutation))
    solution, _ = simulate(started(system, t[0], start[0]), t, "rk8", {"step": STEP_D}, estimate_error=False,
                           label="H_d from the observed rate")
    with stage("H_d from the observed rate: fitting the pole and the torques"):
        return _rate_budget(t, system, solution, orbits, bodies, planets, geodesic, tidal, source)


def _rate_budget(t, system, solution, orbits, bodies, planets, geodesic, tidal, source):
    """from_observed_rate's H_d and budget from its run ``solution`` of ``system`` at ``t``."""
    from ..analysis import nonrigid
    from ..analysis.harmonics import fit_harmonics
    from ..analysis.precession import fit_pole
    from ..orbits.sources import gm_of
    from .earth_pole import PLANETS
    from .earth_tides import rates as tidal_rates

    axis, mean = system.figure_axes("earth", t, solution.y), erfa_pole.from_mean_pole(t, 0.0 * t, 0.0 * t)
    terms = arguments.named(t, erfa_pole.NUTATION_ARGUMENTS)
    iau = erfa_pole.IauPole()(t)
    model_fit, iau_fit = fit_pole(t, *erfa_pole.about_mean_pole(t, axis), terms), fit_pole(
        t, iau["dpsi_rad"], iau["deps_rad"], terms)
    rate = [erfa_pole.PSI_A_RATE_ARCSEC_CY + (model_fit[0].poly[1] - iau_fit[0].poly[1]) / ARCSEC,
            P03_OBLIQUITY_RATE_ARCSEC_CY + (model_fit[1].poly[1] - iau_fit[1].poly[1]) / ARCSEC]
    positions = orbits.positions(t)
    lunisolar, gm = [positions[:, 0], positions[:, 1]], gm_of(("moon", "sun"))
    rate_terms = arguments.named(t, {str(m): m for m in nonrigid.LUNISOLAR_ARGUMENTS})
    at_j2000 = lambda series: fit_harmonics(t, series, rate_terms, degree=2).poly[0]
    on_axis, on_mean = (torque_rates(t, z, lunisolar, gm) for z in (axis, mean))
    second = [at_j2000(a - m) for a, m in zip(on_axis, on_mean)]
    planet_rows = [0.0, 0.0]
    if planets:
        planet_rates = torque_rates(t, mean, [positions[:, k] for k in range(2, len(bodies))],
                                            gm_of(PLANETS))
        planet_rows = [at_j2000(r) for r in planet_rates]
    geodesic_row = -earth.GEODESIC_PRECESSION_ARCSEC_CY if geodesic else 0.0
    nonlinear_row = nonrigid.NONLINEAR_PRECESSION_ARCSEC_CY
    tides = tidal_rates(tidal, source)
    first = rate[0] - second[0] - geodesic_row
    # psi_1 = x F + x^2 S + G + N + T: the root near x = 1
    target = erfa_pole.PSI_A_RATE_ARCSEC_CY - geodesic_row - nonlinear_row - tides[0]
    x = 2.0 * target / (first + math.sqrt(first**2 + 4.0 * second[0] * target))
    return {"h_d": earth.H_D * x, "h_d_iau2006": earth.H_D, "h_d_over_iau2006_minus_1": x - 1.0,
            "psi_rate_target_arcsec_cy": erfa_pole.PSI_A_RATE_ARCSEC_CY,
            "run": "gyroscopic, rk8 2 d, 1950-2050, IAU 2006's H_d, started on the IAU mean pole + REN-2000",
            "longitude_rows_at_h_iau2006_arcsec_cy": {
                "first_order_lunisolar_planets_j4_tilts": first, "of_which_planets_direct": planet_rows[0],
                "second_order": second[0], "geodesic": geodesic_row, "nonlinear_mhb2000": nonlinear_row,
                "tides": tides[0], "total": rate[0] + nonlinear_row + tides[0]},
            "first_order_per_unit_h_arcsec_cy": first / earth.H_D,
            "obliquity_rows_at_h_iau2006_arcsec_cy": {
                "first_order_lunisolar_tilt_b_j4": rate[1] - second[1] - planet_rows[1],
                "planets_direct": planet_rows[1], "second_order": second[1], "tides": tides[1],
                "total": rate[1] + tides[1]},
            "obliquity_rate_p03_arcsec_cy": P03_OBLIQUITY_RATE_ARCSEC_CY,
            "tides": tidal}


def torque_rates(t, poles, positions, gm, h_d=earth.H_D):
    """(dpsi/dt, deps/dt), "/cy, of the Fukushima-Williams angles of the axes ``poles`` (n, 3, GCRS) under the
    point masses' torque alone, H_d (T z) x z / omega (the axes held where they are: the first-order rate);
    ``positions``: per body (n, 3) km, geocentric GCRS; ``gm``: km^3/d^2 per body."""
    zdot = np.zeros_like(poles)
    for r, g in zip(positions, gm):
        dist = np.linalg.norm(r, axis=1)
        tz = (3.0 * g * np.einsum("ij,ij->i", r, poles) / dist**5)[:, None] * r
        zdot += h_d * np.cross(tz, poles) / earth.ERA_RATE_RAD_D
    plus, minus = erfa_pole.pole_angles(t, poles + zdot), erfa_pole.pole_angles(t, poles - zdot)
    return tuple((p - m) / 2.0 * JULIAN_CENTURY_D / ARCSEC for p, m in zip(plus, minus))
