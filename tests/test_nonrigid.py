"""The non-rigid Earth (spinorbit.nonrigid): two-layer response vs closed forms and MHB2000, and the scene.

The scene tests run 2000-2010 (benchmarks/RESULTS.md, "Non-rigid Earth", gives the century).
"""
import dataclasses

import numpy as np
import pytest

from spinorbit import nonrigid
from spinorbit.earth import H_D
from spinorbit.errors import ScenarioError
from spinorbit.results import run_scenario
from tests.units import mas

SCENARIO = "scenarios/earth_precession_nutation_nonrigid.toml"
DECADE = ["span.start=2000-01-01T12:00:00", "span.end=10 yr", "integrator.estimate_error=false", "output.plots=false"]
# terrestrial frequencies (cpsd) of circular nutations from 18.6 yr retrograde to 13.66 d prograde
SIGMAS = -1.0 + np.array([-1 / 6798.4, -1 / 365.26, 1 / 182.62, 1 / 13.66]) / 1.0027379


def test_fcn_period_of_the_model_is_mhb2000s():
    """The free core nutation from the parameters, against MHB2000's -430.21 d (IERS 2010 Table 6.4; Herring's
    MHB_2000 code: -1.00231810920 cpsd, 430.2082 d; Krasna et al. 2013: "conventional -431.39 sidereal days")."""
    _, fcn = nonrigid.normal_modes()
    period = nonrigid.celestial_period_days(fcn)
    published = nonrigid.celestial_period_days(nonrigid.PUBLISHED_FCN_CPSD)
    assert published == pytest.approx(-430.21, abs=0.01)
    # Measured -431.27 d: the two-layer model leaves out the inner core, anelasticity and the oceans,
    # which MHB2000 includes; bound 2 d (0.5 %).
    assert period == pytest.approx(published, abs=2.0)
    # Damping from Im K_CMB: measured 2.08e-5 cpsd against 2.5e-5 (MHB adds inner-core coupling); 30 %.
    assert fcn.imag == pytest.approx(nonrigid.PUBLISHED_FCN_CPSD.imag, rel=0.3)


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


def test_response_peaks_at_the_free_core_nutation():
    _, fcn = nonrigid.normal_modes()
    sigma = np.linspace(-1.004, -1.001, 30001)
    # within the resonance's half width Im(sigma_FCN) (the other factors tilt the peak; measured 3.8e-6)
    assert sigma[np.argmax(np.abs(nonrigid.transfer(sigma)))] == pytest.approx(fcn.real, abs=fcn.imag)


def test_precession_and_the_rigid_parameters_are_left_unchanged():
    assert nonrigid.transfer(-1.0) == pytest.approx(1.0, abs=1e-15)
    assert np.abs(nonrigid.transfer(SIGMAS, nonrigid.RIGID) - 1.0).max() < 1e-15


def test_rigid_mantle_with_fluid_core_matches_its_closed_form():
    """kappa = xi = gamma = beta = 0: T = (s - e) / (s - e - a s (1 + s) / (1 + s + e_f + K)) by hand."""
    p = dataclasses.replace(nonrigid.MHB2000, kappa=0.0, xi=0.0, gamma=0.0, beta=0.0)
    s = SIGMAS
    closed = (s - p.e) / (s - p.e - p.a_f * s * (1 + s) / (1 + s + p.e_f + p.k_cmb))
    assert np.abs(nonrigid.transfer(s, p) - closed).max() < 1e-12


def test_rigid_parameters_return_the_rigid_nutation_exactly():
    t = np.arange(0.0, 3652.5, 2.0)
    rates = np.array([-2 * np.pi / 6798.4, 2 * np.pi / 182.62])
    phases = rates[:, None] * t
    x, y = 1e-4 * np.sin(phases[0]) - 6e-6 * np.sin(phases[1]), 4e-5 * np.cos(phases[0])
    x_out, y_out = nonrigid.nonrigid_nutation(t, x, y, phases, rates, nonrigid.RIGID)
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
    # Rigid 24.9 / 21.8 mas rms; non-rigid measured 1.73 / 1.38 mas.  What the two-layer model leaves
    # out (inner core, anelasticity, oceans) is ~4 mas in the 18.6-yr dpsi (1.5 mas in X), and the
    # precession rate left (-7 mas/cy in psi, RESULTS.md) adds up to 0.3 mas in X over the decade: bound 3 mas.
    assert c["x_rms_mas"] * mas < 3 * mas and c["y_rms_mas"] * mas < 3 * mas


@pytest.mark.parametrize("term, part, bound_mas", [
    ("1 yr", "dpsi_in", 1.0), ("1 yr", "deps_in", 1.0), ("0.5 yr", "dpsi_in", 2.0), ("0.5 yr", "deps_in", 1.0),
    ("27.55 d", "dpsi_in", 0.5), ("13.66 d", "dpsi_in", 0.5), ("13.66 d", "deps_in", 0.5)])
def test_main_terms_against_iau_2000a(decade, term, part, bound_mas):
    """Rigid minus IAU: 1 yr -22 / -8 mas (the FCN resonance), 0.5 yr +40 / -20, 27.55 d -3.4,
    13.66 d +6.2 / -3.0; non-rigid measured within 0.36, 0.06, 1.1, 0.6, 0.08, 0.13, 0.04 mas.  The bounds
    leave room for what the model leaves out (MHB2000's 0.5-yr inner-core and ocean terms ~1 mas)."""
    values = decade[0]["nonrigid"]["terms_mas"][term][part]
    assert abs(values["nonrigid"] - values["iau2000a"]) * mas < bound_mas * mas
    assert abs(values["rigid"] - values["iau2000a"]) > 2 * bound_mas    # the layer does the work
