"""The Earth's H_d from the observed precession rate (scenes/earth_precession_nutation/ellipticity.py): the
model's rate budget against P03's (Capitaine, Wallace & Chapront 2003, A&A 412, 567, Tables 3 and 4), and the
non-rigid scene over the century with it against IAU 2006/2000A and VLBI's pole."""
import pytest

from spinorbit.results import run_scenario
from spinorbit.scenes.earth_precession_nutation.ellipticity import from_observed_rate
from tests.units import arcsec, mas

H_P03 = 3.27379448e-3            # IAU 2006's H_d (P03 Table 4)
PSI_1 = 5038.481507              # P03's psi_1, "/cy


@pytest.fixture(scope="module")
def budget():
    """The non-rigid scene's settings: DE421, planets, J2 rate, J4, geodesic precession and nutation."""
    return from_observed_rate("de421", True, 0.25, True, True, True, True)


def test_h_d_from_the_rate_is_within_the_spread_of_rigid_theories(budget):
    """The first-order constant per unit H is where theories differ: W94 (whose constant gave P03's H_d) and
    Souchay & Kinoshita 1996 by 2.6e-6 for the same rate (Bourda & Capitaine 2004, A&A 428, 691, Table 1).
    Measured: H_d (1 + 6.0e-7)."""
    assert abs(budget["h_d"] / H_P03 - 1.0) < 2.6e-6
    assert budget["h_d"] != H_P03


def test_h_d_gives_the_observed_rate_through_the_budget(budget):
    """psi_1 = x F + x^2 S + G + N at x = H_d / H_0 (the rows at H_0: first order, second order, geodesic,
    nonlinear), to rounding."""
    rows, x = budget["longitude_rows_at_h_iau2006_arcsec_cy"], budget["h_d"] / budget["h_d_iau2006"]
    rate = (x * rows["first_order_lunisolar_planets_j4_tilts"] + x**2 * rows["second_order"] + rows["geodesic"]
            + rows["nonlinear_mhb2000"])
    assert rate * arcsec == pytest.approx(PSI_1 * arcsec, abs=1e-6 * mas)


def test_rows_against_p03_table_3(budget):
    """The model's own rows beside P03's.  Second order: Table 3's (a) + (b), -46.78 mas/cy, is Williams' (1994)
    on an analytical nutation; the model's is its torque on its own axis: within 2 mas/cy (4 % of the row;
    measured -46.15).  The planets' direct torques, +31.367 in longitude and -1.400 in obliquity, fitted as the
    mean of a rate with the planets' periods over a century: within 1 mas/cy (measured +31.72, -1.50).  The
    rate at IAU 2006's H_d is P03's to the first-order constant's 7.5e-7 (3.8 mas/cy; measured -3.0)."""
    rows = budget["longitude_rows_at_h_iau2006_arcsec_cy"]
    assert rows["second_order"] * arcsec == pytest.approx(-0.04678 * arcsec, abs=2 * mas)
    assert rows["of_which_planets_direct"] * arcsec == pytest.approx(0.031367 * arcsec, abs=1 * mas)
    assert rows["geodesic"] == -1.919883 and rows["nonlinear_mhb2000"] == -0.021050
    assert rows["total"] * arcsec == pytest.approx(PSI_1 * arcsec, abs=3.8 * mas)
    obliquity = budget["obliquity_rows_at_h_iau2006_arcsec_cy"]
    assert obliquity["planets_direct"] * arcsec == pytest.approx(-0.001400 * arcsec, abs=1 * mas)


@pytest.mark.slow
def test_nonrigid_earth_over_the_century_with_h_d_from_the_rate():
    """1950-2050 (about 60 s): X within 0.2 mas rms of IAU 2006/2000A (the nutation is not fitted: every main
    term part is within 0.06 mas, benchmarks/results_earth_nonrigid.md; measured 0.09), the psi rate IAU's
    to the fit's noise over the century (0.3 mas/cy), and the model no further from VLBI's X than IAU is plus
    0.1 mas rms (measured 0.26 against 0.26).  Y is the obliquity rate's (RESULTS.md), not asserted here."""
    summary = run_scenario("scenarios/earth_precession_nutation_nonrigid.toml",
                           ["integrator.estimate_error=false", "output.plots=false"]).summary
    c, vlbi = summary["comparison"], summary["vlbi"]["comparison"]["c04"]
    assert c["x_rms_mas"] * mas < 0.2 * mas
    assert abs(c["psi_rate_minus_iau_arcsec_cy"]) * arcsec < 0.3 * mas
    assert (vlbi["model_minus_observed_x_rms_mas"] * mas
            < (vlbi["iau_minus_observed_x_rms_mas"] + 0.1) * mas)


def test_tidal_tilt_adds_williams_rate_to_the_obliquity():
    """earth.tidal_obliquity turns the axes away from the ecliptic pole at +2.4 mas/cy (Williams 1994; P03
    Table 3, tides (c)): the obliquity about the IAU mean pole gains that line, the longitude nothing."""
    import numpy as np

    from spinorbit.references import erfa_pole
    from spinorbit.scenes.earth_precession_nutation.compare import tidal_tilt

    t = np.linspace(-18262.5, 18262.5, 201)
    z = erfa_pole.cip_vector(t)
    (dpsi0, deps0), (dpsi1, deps1) = (erfa_pole.about_mean_pole(t, p) for p in (z, tidal_tilt(t, z, True)))
    century = (t - t[0]) / 36525.0
    assert np.abs((deps1 - deps0) - 0.0024 * arcsec * century).max() < 1e-6 * mas
    assert np.abs(dpsi1 - dpsi0).max() < 1e-6 * mas
    assert tidal_tilt(t, z, False) is z
