"""The non-rigid Earth (spinorbit.analysis.transfer, analysis.nonrigid, earth_nonrigid): MHB2000's own
transfer function (the default) against its table and its rigid limit, the IERS 1996 factors and the
two-layer Earth against each other, closed forms and MHB2000, and the scene over a decade.

The scene tests run 2000-2010 (benchmarks/results_earth_nonrigid.md gives the century).
"""
import dataclasses

import numpy as np
import pytest

from spinorbit.analysis import nonrigid
from spinorbit.analysis.transfer import forms, mhb2000_table
from spinorbit.analysis.transfer.models import (
    IERS1996,
    MHB2000,
    MHB2000_MODES,
    PUBLISHED_FCN_CPSD,
    RIGID,
    TWO_LAYER,
)
from spinorbit.base.errors import ScenarioError
from spinorbit.bodies.earth import H_D
from spinorbit.edge.runner import run_scenario
from tests.units import mas

SCENARIO = "scenarios/earth_precession_nutation_nonrigid.toml"
DECADE = ["span.start=2000-01-01T12:00:00", "span.end=10 yr", "integrator.estimate_error=false",
          "output.plots=false"]
# terrestrial frequencies (cpsd) of circular nutations from 18.6 yr retrograde to 13.66 d prograde
SIGMAS = -1.0 + np.array([-1 / 6798.4, -1 / 365.26, 1 / 182.62, 1 / 13.66]) / 1.0027379
# the resonance form with R = 1 and no resonances: the rigid Earth
RIGID_RESONANCES = dataclasses.replace(IERS1996, r=1.0, r_prime=0.0, modes=tuple(
    dataclasses.replace(m, strength=0.0) for m in IERS1996.modes))
TABLE = np.array([row[2:] for row in mhb2000_table.ROWS])
TABLE_SIGMA, TABLE_T, TABLE_REN_RAD = TABLE[:, 0] - 1.0, TABLE[:, 1] + 1j * TABLE[:, 2], TABLE[:, 5] * 1e-12
H_MHB2000 = 3.27379492e-3   # MHB 2002's (C - A)/C (Bourda & Capitaine 2004, A&A 428, 691, Table 1)


def test_mhb2000_takes_its_tabulated_values_at_the_tabulated_frequencies():
    assert np.array_equal(MHB2000.transfer(TABLE_SIGMA), TABLE_T)
    between = 0.5 * (TABLE_SIGMA[0] + TABLE_SIGMA[1])
    assert MHB2000.transfer(np.array(between)) == MHB2000.between.transfer(between)


def test_resonance_form_reproduces_the_table():
    """The resonance form with MHB2000's free modes at their published frequencies, fitted to the 90
    tabulated values, reproduces each within 0.005 mas on its term (|T_form - T| x REN-2000's amplitude;
    measured 0.0014, the files' rounding being 0.05 prad = 1e-5 mas): one smooth function holds the table to
    well under the 0.05 mas the main terms are aimed at."""
    error = np.abs(MHB2000.between.transfer(TABLE_SIGMA) - TABLE_T) * TABLE_REN_RAD
    assert error.max() < 0.005 * mas


def test_resonance_form_predicts_a_value_left_out():
    """Between the tabulated frequencies: the form fitted without a row predicts it within 0.05 mas on its
    term (measured at most 0.027 mas, the 18.6-yr prograde term's 8", i.e. 3.4e-6 in T)."""
    for k in range(len(TABLE_SIGMA)):
        rest = np.arange(len(TABLE_SIGMA)) != k
        form = forms.fit_resonance(TABLE_SIGMA[rest], TABLE_T[rest], TABLE_REN_RAD[rest], MHB2000_MODES)
        assert abs(form.transfer(TABLE_SIGMA[k]) - TABLE_T[k]) * TABLE_REN_RAD[k] < 0.05 * mas


def test_mhb2000s_fcn_resonance_strength_is_herrings_iers_1996_estimate():
    """The FCN strength fitted to MHB2000's table against T. Herring's, estimated from the VLBI of the 1990s
    for the IERS 1996 series: two estimates, six years apart, agree within 3 % (measured 1.1 %)."""
    fitted = {m.name: m.strength for m in MHB2000.between.modes}["FCN"]
    herring = {m.name: m.strength for m in IERS1996.modes}["FCN"]
    assert abs(fitted / herring - 1) < 0.03


def test_mhb2000_rigid_limit_at_precession_is_the_ratio_of_ellipticities():
    """At sigma = -1 (precession) the non-rigid Earth precesses as a rigid one of its own ellipticity: T is
    relative to REN-2000's rigid amplitudes, so T(-1) = H_MHB2000 / H_REN-2000 = 1 + 1.23e-5.  The form,
    fitted at the nutation frequencies (the nearest 1.5e-4 cpsd away), gives it within 5e-6 (measured 2.8e-6:
    on the 18.6-yr term that is 0.05 mas), and applied to a run of H_d (h / h_d), 1 within 5e-6."""
    t_precession = MHB2000.between.transfer(-1.0)
    assert abs(t_precession - H_MHB2000 / mhb2000_table.RIGID_H) < 5e-6
    assert abs(t_precession * mhb2000_table.RIGID_H / H_D - 1) < 5e-6


@pytest.mark.parametrize("model, bound_d", [
    # Herring's IERS 1996 factors: -430.06 d from the VLBI of the 1990s, MHB2000's -430.21 d from 20 yr.
    (IERS1996, 0.3),
    # Two-layer roots, measured -431.27 d: it leaves out the inner core, anelasticity and the oceans, which
    # MHB2000 includes; bound 2 d (0.5 %).
    (TWO_LAYER, 2.0)])
def test_fcn_period_of_each_model_is_mhb2000s(model, bound_d):
    """The free core nutation of each transfer function, against MHB2000's -430.21 d (IERS 2010 Table 6.4;
    Herring's MHB_2000 code: -1.00231810920 cpsd, 430.2082 d; Krasna et al. 2013: "conventional -431.39
    sidereal days")."""
    _, fcn = model.normal_modes()
    published = forms.celestial_period_days(PUBLISHED_FCN_CPSD)
    assert published == pytest.approx(-430.21, abs=0.01)
    assert forms.celestial_period_days(fcn) == pytest.approx(published, abs=bound_d)
    # Damping: 2.9e-5 (IERS 1996) and 2.08e-5 cpsd (Im K_CMB) against 2.5e-5 (Q 15 000-24 000): 30 %.
    assert fcn.imag == pytest.approx(PUBLISHED_FCN_CPSD.imag, rel=0.3)


@pytest.mark.parametrize("sigma, printed_d", [(-1.00231887299, 430.0665), (-1.00231810920, 430.2082)])
def test_fcn_frequency_to_period_as_herring_prints_it(sigma, printed_d):
    """Herring's nutation routines print their FCN as a pair: "RFCN Freq. -1.00231887299 cyc per sidreal day,
    Period 430.0665 solar days" (the IERS 1996 model) and "-1.00231810920 ..., 430.2082" (MHB_2000); this
    module's conversion gives the same periods (retrograde: negative) to the 4 printed decimals."""
    assert forms.celestial_period_days(complex(sigma)) == pytest.approx(-printed_d, abs=1e-4)


def test_resonance_form_is_the_published_one_in_the_rigid_limit_at_precession():
    """T(-1) = R + A_CW / (-1 - s_CW) + A_FCN / (-1 - s_FCN): the published factors give the precession
    (sigma = -1) its rigid value to 7e-5 (they are rounded VLBI estimates), which fixes the form (with
    R' sigma in place of R' (1 + sigma) it would be 1.3)."""
    assert abs(IERS1996.transfer(-1.0) - 1.0) < 1e-4


@pytest.mark.parametrize("period_d", [-6798.38, 6798.38, -3399.19, 3399.19, -365.26, 365.26, -182.62, 182.62,
                                      -27.55, 27.55, -13.66, 13.66])
def test_two_transfer_functions_agree_at_the_main_terms(period_d):
    """The published resonance form against the two-layer model built from independent parameters, at the
    circular terms of the six main nutations.  The two-layer model leaves out anelasticity, the oceans
    and the inner core: percent-level in T - 1, which reaches 0.33 at the retrograde annual term
    (measured differences 6e-5 to 6.2e-3); bound 1e-2."""
    sigma = -1.0 + 1.0 / (period_d * 1.0027379)
    assert abs(IERS1996.transfer(sigma) - TWO_LAYER.transfer(sigma)) < 1e-2


def test_fluid_core_moment_is_prems_outer_core():
    """A_f/A from PREM's outer-core density (Dziewonski & Anderson 1981, Table 1), integrated here in closed
    form, over A = C (1 - H_d) with C/(M a^2) = 0.3307, GM = 398600.4418 km^3/s^2, a = 6378.1366 km."""
    radius, g = 6371.0e3, 6.67430e-11
    density = np.polynomial.Polynomial([12.5815e3, -1.2638e3 / radius, -3.6426e3 / radius**2,
                                        -5.5281e3 / radius**3])
    moment = (density * np.polynomial.Polynomial([0, 0, 0, 0, 1])).integ()      # kg m^2 per 8 pi / 3
    a_f = 8 * np.pi / 3 * (moment(3480.0e3) - moment(1221.5e3))
    a_earth = 0.3307 * 398600.4418e9 / g * 6378136.6**2 * (1 - H_D)
    # 4 digits, as the parameter is written; G's 2e-5 uncertainty is far below it
    assert TWO_LAYER.a_f == pytest.approx(a_f / a_earth, abs=1e-4)


def test_nonlinear_precession_is_mhb2000s_rate():
    """MHB2000's nonlinear terms add -21 050 uas per century to the precession in longitude (Capitaine,
    Wallace & Chapront 2003, Table 3), nothing at the start."""
    assert nonrigid.nonlinear_precession(0.0) == 0.0
    assert nonrigid.nonlinear_precession(36525.0) == pytest.approx(-21.050 * mas, rel=1e-12)


@pytest.mark.parametrize("model", [IERS1996, TWO_LAYER])
def test_response_peaks_at_the_free_core_nutation(model):
    _, fcn = model.normal_modes()
    sigma = np.linspace(-1.004, -1.001, 30001)
    # within the resonance's half width Im(sigma_FCN) (the other factors tilt the peak; measured 3.8e-6)
    assert sigma[np.argmax(np.abs(model.transfer(sigma)))] == pytest.approx(fcn.real, abs=fcn.imag)


def test_precession_and_the_rigid_parameters_are_left_unchanged():
    assert TWO_LAYER.transfer(-1.0) == pytest.approx(1.0, abs=1e-15)
    assert np.abs(RIGID.transfer(SIGMAS) - 1.0).max() < 1e-15
    assert np.abs(RIGID_RESONANCES.transfer(SIGMAS) - 1.0).max() == 0.0


def test_rigid_mantle_with_fluid_core_matches_its_closed_form():
    """kappa = xi = gamma = beta = 0: T = (s - e) / (s - e - a s (1 + s) / (1 + s + e_f + K)) by hand."""
    p = dataclasses.replace(TWO_LAYER, kappa=0.0, xi=0.0, gamma=0.0, beta=0.0)
    s = SIGMAS
    closed = (s - p.e) / (s - p.e - p.a_f * s * (1 + s) / (1 + s + p.e_f + p.k_cmb))
    assert np.abs(p.transfer(s) - closed).max() < 1e-12


RIGID_TABLE = forms.Tabulated(TABLE_SIGMA, np.ones(len(TABLE_SIGMA), complex),
                              np.zeros(len(TABLE_SIGMA), complex), RIGID_RESONANCES, H_D)


@pytest.mark.parametrize("rigid", [RIGID, RIGID_RESONANCES, RIGID_TABLE])
def test_rigid_parameters_return_the_rigid_nutation_exactly(rigid):
    """The rigid limit of each form, including a table of ones relative to the run's own H: the layer returns
    the rigid nutation bit for bit."""
    t = np.arange(0.0, 3652.5, 2.0)
    rates = np.array([-2 * np.pi / 6798.4, 2 * np.pi / 182.62])
    phases = rates[:, None] * t
    x, y = 1e-4 * np.sin(phases[0]) - 6e-6 * np.sin(phases[1]), 4e-5 * np.cos(phases[0])
    x_out, y_out = nonrigid.nonrigid_nutation(t, x, y, phases, rates, rigid, H_D)
    assert np.array_equal(x_out, x) and np.array_equal(y_out, y)


def test_kinematic_part_is_not_scaled():
    """A frame's turn (the geodesic nutation) passed as ``kinematic`` comes out as it went in."""
    t = np.arange(0.0, 3652.5, 2.0)
    rates = np.array([2 * np.pi / 365.26])
    phases = rates[:, None] * t
    turn = 6e-11 * np.sin(phases[0])
    x_out, _ = nonrigid.nonrigid_nutation(t, turn, 0 * t, phases, rates, IERS1996, H_D, (turn, 0.0))
    assert np.abs(x_out - turn).max() < 1e-20


def test_nonrigid_needs_the_de421_arguments():
    with pytest.raises(ScenarioError, match="earth.nonrigid"):
        run_scenario("scenarios/earth_precession_nutation_circular.toml", ["earth.nonrigid=true"])


def test_unknown_transfer_function_is_a_scenario_error():
    with pytest.raises(ScenarioError, match="earth.transfer_function"):
        run_scenario(SCENARIO, DECADE + ["earth.transfer_function=mhb2010"])


@pytest.fixture(scope="module")
def decade():
    """2000-2010 with the layer on and off (the same rigid integration)."""
    return (run_scenario(SCENARIO, DECADE).summary,
            run_scenario(SCENARIO, DECADE + ["earth.nonrigid=false"]).summary)


def test_layer_off_gives_the_rigid_figures_exactly(decade):
    on, off = decade
    assert off["comparison"]["x_rms_mas"] == on["nonrigid"]["rigid_x_rms_mas"]
    assert off["comparison"]["y_rms_mas"] == on["nonrigid"]["rigid_y_rms_mas"]
    assert "nonrigid" not in off and "vlbi" not in off


def test_cip_against_iau_2006_2000a_over_a_decade(decade):
    on, _ = decade
    c = on["comparison"]
    # Rigid 24.9 / 21.8 mas rms; non-rigid (MHB2000) measured 1.11 / 0.13 mas.  A decade does not separate the
    # 18.6-yr term from the quadratic, and what the quadratic takes is not scaled by T (T - 1 = -0.3 % of 6.9"
    # in X at most); the precession rate left (-3 mas/cy in psi) adds up to 0.1 mas in X: bound 2 mas.
    assert c["x_rms_mas"] * mas < 2 * mas and c["y_rms_mas"] * mas < 2 * mas


def test_each_printed_difference_is_the_difference_of_the_printed_values(decade):
    """The summary's model - IAU of each main term is its model value minus its IAU value as printed beside it
    (both fitted alike; the published coefficient is printed apart, under its own name)."""
    c = decade[0]["comparison"]
    differences = [key for key in c if key.endswith("_model_minus_iau_mas")]
    assert len(differences) >= 4
    for key in differences:
        stem = key.removesuffix("_model_minus_iau_mas")
        model, iau = c[f"{stem}_model_arcsec"], c[f"{stem}_iau2000a_arcsec"]
        assert c[key] * mas == pytest.approx((model - iau) * 1000 * mas, abs=1e-9 * mas)
    # the published coefficients, under their own name: IERS Conventions 2010 Table 5.3a (IAU 2000A)
    assert c["nutation_0_5yr_dpsi_iau2000a_published_arcsec"] == -1.3170906
    assert c["nutation_13_66d_deps_iau2000a_published_arcsec"] == 0.0978459


# The gyroscopic model recovers the figure axis from L to second order in the nutation's frequency over the
# spin; the third order, (nu / Omega)^3 of each circular term, is 0.09 mas at 13.66 d (dpsi in phase; the full
# model with the daily spin, 2000-2010, differs from it by -0.092): bound 0.15 there, 0.1 mas elsewhere.
GYROSCOPIC_THIRD_ORDER_MAS = {("13.66 d", "dpsi_in"): 0.15}


@pytest.mark.parametrize("term, part", [
    ("1 yr", "deps_in"), ("0.5 yr", "dpsi_in"), ("0.5 yr", "deps_in"), ("0.5 yr", "dpsi_out"),
    ("0.5 yr", "deps_out"), ("27.55 d", "dpsi_in"), ("13.66 d", "dpsi_in"), ("13.66 d", "deps_in"),
    ("13.66 d", "dpsi_out")])
def test_main_terms_against_iau_2000a(decade, term, part):
    """Within 0.1 mas of IAU 2000A (the issue's target) with MHB2000's transfer function; rigid minus IAU:
    1 yr -8 mas in deps (the FCN resonance), 0.5 yr +40 / -20 (out of phase +1.3 / +0.5), 27.55 d -3.4,
    13.66 d +6.2 / -3.0 (out of phase -0.3).  The 1-yr dpsi (rigid -22 mas) is not asserted here: a decade's
    fit gives it -0.16 mas, the century's -0.05 (the fitted 1-yr term holds the unresolved 365.22-d one and,
    over a decade, part of the 346.6-d and 386-d ones)."""
    values = decade[0]["nonrigid"]["terms_mas"][term][part]
    bound = GYROSCOPIC_THIRD_ORDER_MAS.get((term, part), 0.1)
    assert abs(values["nonrigid"] - values["iau2000a"]) * mas < bound * mas
    assert abs(values["rigid"] - values["iau2000a"]) > 0.25      # the layer does the work


@pytest.mark.parametrize("term, part", [
    ("1 yr", "dpsi_in"), ("1 yr", "deps_in"), ("0.5 yr", "dpsi_in"), ("0.5 yr", "deps_in"),
    ("0.5 yr", "dpsi_out"), ("27.55 d", "dpsi_in"), ("27.55 d", "deps_in"), ("13.66 d", "dpsi_in"),
    ("13.66 d", "deps_in")])
def test_rigid_run_is_ren2000(decade, term, part):
    """The rigid run against REN-2000 (scaled to the run's H_d, plus the model's geodesic nutation, which
    REN-2000 has not) within 0.05 mas, the gyroscopic model's third order aside (above)."""
    values = decade[0]["nonrigid"]["terms_mas"][term][part]
    bound = GYROSCOPIC_THIRD_ORDER_MAS.get((term, part), 0.05)
    assert abs(values["rigid"] - values["ren2000"]) * mas < bound * mas


def test_iau_2000a_against_vlbi_over_the_decade(decade):
    """The observed pole offsets read as IAU 2006/2000A + (dX, dY): IAU 2000A's residual against VLBI is
    about 0.2 mas rms (MHB 2002's fit), the free core nutation's 0.1-0.3 mas among it: taking out Lambert's
    FCN model lowers it.  Measured 2000-2010: 0.18 / 0.22 mas, 0.14 / 0.18 without the FCN."""
    vlbi = decade[0]["vlbi"]["comparison"]
    for axis in "xy":
        assert 0.05 < vlbi["c04"][f"iau_minus_observed_{axis}_rms_mas"] < 0.4
        assert (vlbi["fcn_span_fcn_removed"][f"iau_minus_observed_{axis}_rms_mas"]
                < vlbi["fcn_span_with_fcn"][f"iau_minus_observed_{axis}_rms_mas"])
