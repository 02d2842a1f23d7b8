"""The non-rigid Earth (spinorbit.nonrigid): the published resonance form (IERS 1996 factors, the default) and the
two-layer model (MHB2000 parameters) against each other, closed forms and MHB2000, and the scene.

The scene tests run 2000-2010 (benchmarks/RESULTS.md, "Non-rigid Earth", gives the century).
"""
import dataclasses

import numpy as np
import pytest

from spinorbit import nonrigid
from spinorbit.bodies.earth import H_D
from spinorbit.errors import ScenarioError
from spinorbit.results import run_scenario
from tests.units import mas

SCENARIO = "scenarios/earth_precession_nutation_nonrigid.toml"
DECADE = ["span.start=2000-01-01T12:00:00", "span.end=10 yr", "integrator.estimate_error=false", "output.plots=false"]
# terrestrial frequencies (cpsd) of circular nutations from 18.6 yr retrograde to 13.66 d prograde
SIGMAS = -1.0 + np.array([-1 / 6798.4, -1 / 365.26, 1 / 182.62, 1 / 13.66]) / 1.0027379
# the resonance form with R = 1 and no resonances: the rigid Earth
RIGID_RESONANCES = dataclasses.replace(nonrigid.IERS1996, r=1.0, r_prime=0.0, chandler_strength=0.0, fcn_strength=0.0)


@pytest.mark.parametrize("model, bound_d", [
    # Herring's IERS 1996 factors: -430.06 d from the VLBI of the 1990s, MHB2000's -430.21 d from 20 yr: 0.3 d.
    (nonrigid.IERS1996, 0.3),
    # Two-layer roots, measured -431.27 d: it leaves out the inner core, anelasticity and the oceans, which
    # MHB2000 includes; bound 2 d (0.5 %).
    (nonrigid.MHB2000, 2.0)])
def test_fcn_period_of_each_model_is_mhb2000s(model, bound_d):
    """The free core nutation of each transfer function, against MHB2000's -430.21 d (IERS 2010 Table 6.4;
    Herring's MHB_2000 code: -1.00231810920 cpsd, 430.2082 d; Krasna et al. 2013: "conventional -431.39
    sidereal days")."""
    _, fcn = nonrigid.normal_modes(model)
    published = nonrigid.celestial_period_days(nonrigid.PUBLISHED_FCN_CPSD)
    assert published == pytest.approx(-430.21, abs=0.01)
    assert nonrigid.celestial_period_days(fcn) == pytest.approx(published, abs=bound_d)
    # Damping: 2.9e-5 (IERS 1996) and 2.08e-5 cpsd (Im K_CMB) against 2.5e-5 (Q 15 000-24 000): 30 %.
    assert fcn.imag == pytest.approx(nonrigid.PUBLISHED_FCN_CPSD.imag, rel=0.3)


@pytest.mark.parametrize("sigma, printed_d", [(-1.00231887299, 430.0665), (-1.00231810920, 430.2082)])
def test_fcn_frequency_to_period_as_herring_prints_it(sigma, printed_d):
    """Herring's nutation routines print their FCN as a pair: "RFCN Freq. -1.00231887299 cyc per sidreal day,
    Period 430.0665 solar days" (the IERS 1996 model) and "-1.00231810920 ..., 430.2082" (MHB_2000); this
    module's conversion gives the same periods (retrograde: negative) to the 4 printed decimals."""
    assert nonrigid.celestial_period_days(complex(sigma)) == pytest.approx(-printed_d, abs=1e-4)


def test_resonance_form_is_the_published_one_in_the_rigid_limit_at_precession():
    """T(-1) = R + A_CW / (-1 - s_CW) + A_FCN / (-1 - s_FCN): the published factors give the precession
    (sigma = -1) its rigid value to 7e-5 (they are rounded VLBI estimates), which fixes the form (with
    R' sigma in place of R' (1 + sigma) it would be 1.3)."""
    assert abs(nonrigid.transfer(-1.0, nonrigid.IERS1996) - 1.0) < 1e-4


@pytest.mark.parametrize("period_d", [-6798.38, 6798.38, -3399.19, 3399.19, -365.26, 365.26, -182.62, 182.62,
                                      -27.55, 27.55, -13.66, 13.66])
def test_two_transfer_functions_agree_at_the_main_terms(period_d):
    """The published resonance form against the two-layer model built from independent parameters, at the
    circular terms of the six main nutations.  The two-layer model leaves out anelasticity, the oceans
    and the inner core: percent-level in T - 1, which reaches 0.33 at the retrograde annual term
    (measured differences 6e-5 to 6.2e-3); bound 1e-2."""
    sigma = -1.0 + 1.0 / (period_d * 1.0027379)
    assert abs(nonrigid.transfer(sigma, nonrigid.IERS1996) - nonrigid.transfer(sigma, nonrigid.MHB2000)) < 1e-2


def test_fluid_core_moment_is_prems_outer_core():
    """A_f/A from PREM's outer-core density (Dziewonski & Anderson 1981, Table 1), integrated here in closed
    form, over A = C (1 - H_d) with C/(M a^2) = 0.3307, GM = 398600.4418 km^3/s^2, a = 6378.1366 km."""
    radius, g = 6371.0e3, 6.67430e-11
    density = np.polynomial.Polynomial([12.5815e3, -1.2638e3 / radius, -3.6426e3 / radius**2, -5.5281e3 / radius**3])
    moment = (density * np.polynomial.Polynomial([0, 0, 0, 0, 1])).integ()      # kg m^2 per 8 pi / 3
    a_f = 8 * np.pi / 3 * (moment(3480.0e3) - moment(1221.5e3))
    a_earth = 0.3307 * 398600.4418e9 / g * 6378136.6**2 * (1 - H_D)
    # 4 digits, as the parameter is written; G's 2e-5 uncertainty is far below it
    assert nonrigid.MHB2000.a_f == pytest.approx(a_f / a_earth, abs=1e-4)


def test_nonlinear_precession_is_mhb2000s_rate():
    """MHB2000's nonlinear terms add -21 050 uas per century to the precession in longitude (Capitaine,
    Wallace & Chapront 2003, Table 3), nothing at the start."""
    assert nonrigid.nonlinear_precession(0.0) == 0.0
    assert nonrigid.nonlinear_precession(36525.0) == pytest.approx(-21.050 * mas, rel=1e-12)


@pytest.mark.parametrize("model", [nonrigid.IERS1996, nonrigid.MHB2000])
def test_response_peaks_at_the_free_core_nutation(model):
    _, fcn = nonrigid.normal_modes(model)
    sigma = np.linspace(-1.004, -1.001, 30001)
    # within the resonance's half width Im(sigma_FCN) (the other factors tilt the peak; measured 3.8e-6)
    assert sigma[np.argmax(np.abs(nonrigid.transfer(sigma, model)))] == pytest.approx(fcn.real, abs=fcn.imag)


def test_precession_and_the_rigid_parameters_are_left_unchanged():
    assert nonrigid.transfer(-1.0, nonrigid.MHB2000) == pytest.approx(1.0, abs=1e-15)
    assert np.abs(nonrigid.transfer(SIGMAS, nonrigid.RIGID) - 1.0).max() < 1e-15
    assert np.abs(nonrigid.transfer(SIGMAS, RIGID_RESONANCES) - 1.0).max() == 0.0


def test_rigid_mantle_with_fluid_core_matches_its_closed_form():
    """kappa = xi = gamma = beta = 0: T = (s - e) / (s - e - a s (1 + s) / (1 + s + e_f + K)) by hand."""
    p = dataclasses.replace(nonrigid.MHB2000, kappa=0.0, xi=0.0, gamma=0.0, beta=0.0)
    s = SIGMAS
    closed = (s - p.e) / (s - p.e - p.a_f * s * (1 + s) / (1 + s + p.e_f + p.k_cmb))
    assert np.abs(nonrigid.transfer(s, p) - closed).max() < 1e-12


@pytest.mark.parametrize("rigid", [nonrigid.RIGID, RIGID_RESONANCES])
def test_rigid_parameters_return_the_rigid_nutation_exactly(rigid):
    t = np.arange(0.0, 3652.5, 2.0)
    rates = np.array([-2 * np.pi / 6798.4, 2 * np.pi / 182.62])
    phases = rates[:, None] * t
    x, y = 1e-4 * np.sin(phases[0]) - 6e-6 * np.sin(phases[1]), 4e-5 * np.cos(phases[0])
    x_out, y_out = nonrigid.nonrigid_nutation(t, x, y, phases, rates, rigid)
    assert np.array_equal(x_out, x) and np.array_equal(y_out, y)


def test_nonrigid_needs_the_de421_arguments():
    with pytest.raises(ScenarioError, match="earth.nonrigid"):
        run_scenario("scenarios/earth_precession_nutation_circular.toml", ["earth.nonrigid=true"])


@pytest.fixture(scope="module")
def decade():
    """2000-2010 with the layer on and off (the same rigid integration)."""
    return (run_scenario(SCENARIO, DECADE).summary,
            run_scenario(SCENARIO, DECADE + ["earth.nonrigid=false"]).summary)


def test_layer_off_gives_the_rigid_figures_exactly(decade):
    on, off = decade
    assert off["comparison"]["x_rms_mas"] == on["nonrigid"]["rigid_x_rms_mas"]
    assert off["comparison"]["y_rms_mas"] == on["nonrigid"]["rigid_y_rms_mas"]
    assert "nonrigid" not in off


def test_cip_against_iau_2006_2000a_over_a_decade(decade):
    on, off = decade
    c = on["comparison"]
    # Rigid 24.9 / 21.8 mas rms; non-rigid (IERS 1996 resonance factors) measured 1.17 / 0.13 mas.  A decade
    # does not separate the 18.6-yr term from the quadratic, and what the quadratic takes is not scaled by T
    # (T - 1 = -0.3 % of 6.9" in X at most); the precession rate left (-3 mas/cy in psi, RESULTS.md) adds up
    # to 0.1 mas in X: bound 2 mas.
    assert c["x_rms_mas"] * mas < 2 * mas and c["y_rms_mas"] * mas < 2 * mas


@pytest.mark.parametrize("term, part", [
    ("1 yr", "dpsi_in"), ("1 yr", "deps_in"), ("0.5 yr", "dpsi_in"), ("0.5 yr", "deps_in"), ("0.5 yr", "dpsi_out"),
    ("27.55 d", "dpsi_in"), ("13.66 d", "dpsi_in"), ("13.66 d", "deps_in")])
def test_main_terms_against_iau_2000a(decade, term, part):
    """Within 0.5 mas of IAU 2000A (the issue's target).  Rigid minus IAU: 1 yr -22 / -8 mas (the FCN
    resonance), 0.5 yr +40 / -20 (out of phase +1.3), 27.55 d -3.4, 13.66 d +6.2 / -3.0; non-rigid measured
    within 0.02, 0.05, 0.03, 0.04, 0.03, 0.02, 0.04, 0.02 mas."""
    values = decade[0]["nonrigid"]["terms_mas"][term][part]
    assert abs(values["nonrigid"] - values["iau2000a"]) * mas < 0.5 * mas
    assert abs(values["rigid"] - values["iau2000a"]) > 1.0      # the layer does the work
