"""The non-rigid Earth at 0.1 mas: benchmarks/results_earth_nonrigid.md's figures but the precession budget.

Run: ``python benchmarks/earth_nonrigid.py`` (four 1950-2050 runs of the non-rigid scenario, one per transfer
function and one rigid, and two 2000-2010 runs of the full and gyroscopic models; about 3 min, shared core).
Prints Markdown:

* CIP X, Y against IAU 2006/2000A for each transfer function, as the scene gives them, and with a line taken
  out (what the precession and obliquity rates left make);
* the 24 main term parts: the non-rigid pole minus IAU 2000A for each transfer function;
* the rigid run against REN-2000 (scaled by H_d / H_REN-2000, with the model's geodesic nutation; the
  gyroscopic model's figure axis carries its third-order term itself), beside the full model (daily spin
  resolved) minus the gyroscopic one over 2000-2010;
* the pole against VLBI's (IERS EOP 20 C04), with Lambert's FCN model and without, and per decade;
* the rates' budget at J2000 (the H_d from the observed rate) beside P03's, DE421's tides band by band;
* the MHB2000 resonance form against its table.
"""
import numpy as np

from spinorbit.analysis import nonrigid
from spinorbit.analysis.precession import fit_pole, term_table
from spinorbit.analysis.transfer import forms, mhb2000_table
from spinorbit.analysis.transfer.models import IERS1996, MHB2000, MHB2000_MODES
from spinorbit.base.constants import JULIAN_CENTURY_D, MAS
from spinorbit.bodies import earth
from spinorbit.comparisons.earth_nonrigid import TABLE_TERMS, ren2000_scaled
from spinorbit.edge.runner import run_scenario
from spinorbit.orbits.sources import DE421
from spinorbit.references import arguments, erfa_pole, vlbi_pole
from spinorbit.starts import earth_tides as tides

SCENARIO = "scenarios/earth_precession_nutation_nonrigid.toml"
QUIET = ["integrator.estimate_error=false", "output.plots=false"]
MODELS = ("mhb2000", "iers1996", "two_layer")
PARTS = ("dpsi_in", "dpsi_out", "deps_in", "deps_out")
H_MHB2000 = 3.27379492e-3        # MHB 2002's (C - A)/C (Bourda & Capitaine 2004, A&A 428, 691, Table 1)


def poles(result):
    """(t TDB days, pole (n, 3) GCRS) of a run's table."""
    t = np.asarray(result.table["time"].tdb.jd - 2451545.0)
    x, y = (np.asarray(result.table[k].to_value("rad")) for k in ("cip_x", "cip_y"))
    return t, np.column_stack([x, y, np.sqrt(1.0 - x**2 - y**2)])


def century(model):
    """(summary, t, z): the scenario's run with ``model`` (None: the layer off)."""
    overrides = ["earth.nonrigid=false"] if model is None else [f"earth.transfer_function={model}"]
    result = run_scenario(SCENARIO, overrides + QUIET)
    return (result.summary, *poles(result))


def detrended_rms(t, residual):
    big_t = t / JULIAN_CENTURY_D
    line = np.polyval(np.polyfit(big_t, residual, 1), big_t)
    return float(np.sqrt(np.mean((residual - line) ** 2)))


def parts(t, series):
    """term -> part -> name -> mas, fitted as the scene fits (quadratic + the resolved arguments)."""
    terms = arguments.named(t, {str(m): m for m in nonrigid.LUNISOLAR_ARGUMENTS})
    return term_table({name: fit_pole(t, *v, terms) for name, v in series.items()},
                      {name: str(m) for name, m in TABLE_TERMS.items()})


def full_minus_gyroscopic():
    """13.66 d, 9.13 d, 13.63 d (dpsi in, deps in), mas: the full model minus the gyroscopic, 2000-2010."""
    fits = {}
    for model, step in (("full", "0.05 d"), ("gyroscopic", "1 d")):
        t, z = poles(run_scenario("scenarios/earth_precession_nutation_full.toml", QUIET + [
            f"earth.model={model}", f"integrator.step={step}", "span.step=0.25 d"]))
        terms = arguments.named(t, {str(m): m for m in nonrigid.LUNISOLAR_ARGUMENTS})
        fits[model] = fit_pole(t, *erfa_pole.about_mean_pole(t, z), terms)
    key = {"13.66 d": "(0, 0, 2, 0, 2)", "9.13 d": "(1, 0, 2, 0, 2)", "13.63 d": "(0, 0, 2, 0, 1)"}
    return {name: tuple((getattr(fits["full"][i], trig)[k] - getattr(fits["gyroscopic"][i], trig)[k]) / MAS
                        for i, trig in ((0, "sin"), (1, "cos"))) for name, k in key.items()}


def print_cip(runs, rigid_summary, t, iau):
    print("| transfer function | X rms | Y rms | X / Y rms, a line taken out | psi rate - P03 "
          "| obliquity rate - P03 |\n|---|---|---|---|---|---|")
    for model, (summary, _, z) in runs.items():
        c = summary["comparison"]
        dx, dy = ((z[:, i] - iau[k]) / MAS for i, k in ((0, "cip_x_rad"), (1, "cip_y_rad")))
        print(f"| {model} | {c['x_rms_mas']:.3f} | {c['y_rms_mas']:.3f} | {detrended_rms(t, dx):.3f} / "
              f"{detrended_rms(t, dy):.3f} | {1000 * c['psi_rate_minus_iau_arcsec_cy']:+.2f} mas/cy | "
              f"{1000 * c['obliquity_rate_minus_iau_arcsec_cy']:+.2f} mas/cy |")
    c = rigid_summary["comparison"]
    print(f"| (rigid, layer off) | {c['x_rms_mas']:.2f} | {c['y_rms_mas']:.2f} | | | |")


def print_terms(runs):
    """The parts of each transfer function's pole minus IAU 2000A."""
    print("\n| term | part | rigid | IAU 2000A | " + " | ".join(f"{m} - IAU" for m in MODELS)
          + " |\n|---|---|---|---|" + "---|" * len(MODELS))
    tables = {model: summary["nonrigid"]["terms_mas"] for model, (summary, _, _) in runs.items()}
    for term in TABLE_TERMS:
        for part in PARTS:
            v = tables["mhb2000"][term][part]
            diffs = " | ".join(f"{tables[m][term][part]['nonrigid'] - v['iau2000a']:+.3f}" for m in MODELS)
            print(f"| {term} | {part} | {v['rigid']:.3f} | {v['iau2000a']:.3f} | {diffs} |")


def print_ren2000(t, z_rigid, h_d):
    ren = parts(t, {"rigid": erfa_pole.about_mean_pole(t, z_rigid), "ren": ren2000_scaled(t, h_d, True)})
    print("\n| term | part | rigid | REN-2000 x H_d/H | rigid - REN |\n|---|---|---|---|---|")
    for term in TABLE_TERMS:
        for part in PARTS:
            v = ren[term][part]
            print(f"| {term} | {part} | {v['rigid']:.3f} | {v['ren']:.3f} | {v['rigid'] - v['ren']:+.3f} |")
    main = ren["18.6 yr"]["dpsi_in"]
    ratio = main["rigid"] / (main["ren"] * mhb2000_table.RIGID_H / h_d)
    print(f"\n18.6-yr dpsi in phase: rigid / REN-2000 - 1 = {ratio - 1:.4e}, H_d / H_REN-2000 - 1 = "
          f"{h_d / mhb2000_table.RIGID_H - 1:.4e}: rigid / (REN-2000 x H_d / H_REN) - 1 = "
          f"{main['rigid'] / main['ren'] - 1:+.1e}")
    print("full - gyroscopic, 2000-2010 (dpsi in, deps in, mas): " + "; ".join(
        f"{name} {a:+.4f} {b:+.4f}" for name, (a, b) in full_minus_gyroscopic().items()))


def print_vlbi(summary):
    vlbi = summary["vlbi"]["comparison"]
    print("\n| span | n | model - VLBI X / Y rms | IAU 2000A - VLBI X / Y rms |\n|---|---|---|---|")
    for label, key in (("C04 1984-2026 (all)", "c04"), ("FCN model's span 1984-2013", "fcn_span_with_fcn"),
                       ("the same, Lambert's FCN out of VLBI", "fcn_span_fcn_removed")):
        r = vlbi[key]
        print(f"| {label} | {r['n']} | {r['model_minus_observed_x_rms_mas']:.3f} / "
              f"{r['model_minus_observed_y_rms_mas']:.3f} | {r['iau_minus_observed_x_rms_mas']:.3f} / "
              f"{r['iau_minus_observed_y_rms_mas']:.3f} |")
    print("\n| decade | n | model - VLBI X / Y rms | IAU 2000A - VLBI X / Y rms |\n|---|---|---|---|")
    for decade, r in vlbi["per_decade"].items():
        print(f"| {decade} | {r['n']} | {r['model_minus_observed_x_rms_mas']:.3f} / "
              f"{r['model_minus_observed_y_rms_mas']:.3f} | {r['iau_minus_observed_x_rms_mas']:.3f} / "
              f"{r['iau_minus_observed_y_rms_mas']:.3f} |")
    size = vlbi["fcn_size_mas"]
    print(f"FCN (Lambert) over 1984-2013: X / Y rms {size['x_rms']:.3f} / {size['y_rms']:.3f} mas, at most "
          f"{size['max']:.3f} mas")
    observed = vlbi_pole.offsets()
    big_t = observed.t_tdb_d / JULIAN_CENTURY_D
    dx, dy = (np.polyfit(big_t, v / MAS, 1)[0] for v in (observed.dx, observed.dy))
    print(f"VLBI - IAU 2006/2000A over the C04 span, lines fitted: dX {dx:+.2f}, dY {dy:+.2f} mas/cy")


def print_form():
    table = np.array([row[2:] for row in mhb2000_table.ROWS])
    sigma, values, ren_rad = table[:, 0] - 1.0, table[:, 1] + 1j * table[:, 2], table[:, 5] * 1e-12
    inside = np.abs(MHB2000.between.transfer(sigma) - values) * ren_rad / MAS
    left_out = [abs(forms.fit_resonance(np.delete(sigma, k), np.delete(values, k), np.delete(ren_rad, k),
                                        MHB2000_MODES).transfer(sigma[k]) - values[k]) * ren_rad[k] / MAS
                for k in range(len(sigma))]
    fewer = {}
    for left in ("FICN", "CW"):
        modes = {name: s for name, s in MHB2000_MODES.items() if name != left}
        form = forms.fit_resonance(sigma, values, ren_rad, modes)
        fewer[left] = (np.abs(form.transfer(sigma) - values) * ren_rad / MAS).max()
    fitted = {m.name: m.strength for m in MHB2000.between.modes}["FCN"]
    herring = {m.name: m.strength for m in IERS1996.modes}["FCN"]
    print(f"\nResonance form (R, R', CW, FCN, FICN at MHB2000's frequencies) on the {len(sigma)} tabulated "
          f"values: |T_form - T| x REN amplitude at most {inside.max():.4f} mas (rms "
          f"{np.sqrt(np.mean(inside**2)):.4f}); each left out and predicted: at most {max(left_out):.4f} "
          "mas; "
          f"T(-1) - 1 = {MHB2000.between.transfer(-1.0).real - 1:.2e} (H_MHB2000 / H_REN-2000 - 1 = "
          f"{H_MHB2000 / mhb2000_table.RIGID_H - 1:.2e}); A_FCN {fitted:.4e}, IERS 1996's "
          f"{herring:.4e}; without the FICN at most {fewer['FICN']:.4f} mas, without the CW "
          f"{fewer['CW']:.4f}")


P03_LONGITUDE = {"first_order_lunisolar_planets_j4_tilts": 5494.062986 * np.cos(np.radians(84381.406 / 3600))
                 - 0.269430 + 0.031367 + 0.002600, "second_order": -0.046780, "geodesic": -1.919883,
                 "nonlinear_mhb2000": -0.021050, "tides": 0.0, "total": 5038.481507}   # P03 Tables 3, 4
P03_OBLIQUITY = {"planets_direct": -0.001400, "second_order": 0.0, "tides": 0.002400, "total": -0.025754}


def print_budget(summary):
    """The rates' rows at J2000 at IAU 2006's H_d (the summary's dynamical_ellipticity) beside P03's, "/cy, and
    DE421's tides band by band."""
    budget = summary["dynamical_ellipticity"]
    print(f"\nH_d from the observed rate: {budget['h_d']:.8e} (IAU 2006's x (1 "
          f"{budget['h_d_over_iau2006_minus_1']:+.3e}))\n\n| row | longitude model | P03 | obliquity model | P03 |"
          "\n|---|---|---|---|---|")
    psi, eps = (budget[f"{k}_rows_at_h_iau2006_arcsec_cy"] for k in ("longitude", "obliquity"))
    for row in (*psi, *(k for k in eps if k not in psi)):
        cells = [f"{d[row]:+.6f}" if row in d else "" for d in (psi, P03_LONGITUDE, eps, P03_OBLIQUITY)]
        print(f"| {row} | " + " | ".join(cells) + " |")
    love = earth.de421_tides()
    one = lambda band, delay: tides.model_rates(DE421(), tuple(
        (love[b][0] if b == band else 0.0, love[b][1] * delay) for b in (0, 1, 2)))
    bands = [[d - e for d, e in zip(one(band, 1.0), one(band, 0.0))] for band in (0, 1, 2)]
    print("The delays of DE421's tides by band (zonal, diurnal, semi-diurnal), mas/cy: psi " + ", ".join(
        f"{1000 * b[0]:+.3f}" for b in bands) + "; eps " + ", ".join(f"{1000 * b[1]:+.3f}" for b in bands))


def main():
    runs = {model: century(model) for model in MODELS}
    rigid_summary, t, z_rigid = century(None)
    iau = erfa_pole.IauPole()(t)
    print_cip(runs, rigid_summary, t, iau)
    print_terms(runs)
    print_ren2000(t, z_rigid, rigid_summary["dynamical_ellipticity"]["h_d"])
    print_vlbi(runs["mhb2000"][0])
    print_budget(runs["mhb2000"][0])
    print_form()


if __name__ == "__main__":
    main()
