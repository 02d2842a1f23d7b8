"""Mercury's spin (scenes/mercury_spin): the Cassini-state obliquity and the 88-d libration on DE421's orbit against
the radar (Margot et al. 2012) and the altimeter (Stark et al. 2015), the libration's closed form, Peale's equation
with the orbit's node precession scaled, and a start away from the state settling to the same state.

Twenty years at the radar's epoch (2000-2020) keep it fast; the century's figures are in benchmarks/RESULTS.md.
"""
import math

import pytest

from spinorbit.analysis.cassini import eccentricity_functions, peale_obliquity, precession_constant
from spinorbit.bodies import mercury
from spinorbit.edge.runner import run_scenario
from tests.units import arcsec

ARCMIN = 60 * arcsec
SPAN = ["span.start=2000-01-01", "span.end=2020-01-01", "integrator.estimate_error=false", "output.plots=false"]


@pytest.fixture(scope="module")
def run():
    return run_scenario("scenarios/mercury_spin.toml", [*SPAN, "precession.scales=[0, 2]"]).summary


def test_g201_by_quadrature_is_hansens_series():
    """G201 = 7e/2 - 123e^3/16 + 489e^5/128 (Kaula 1966, the 3:2 resonant coefficient) to its e^7 term."""
    e = 0.2056
    assert eccentricity_functions(e)[1] == pytest.approx(7 * e / 2 - 123 * e**3 / 16 + 489 * e**5 / 128,
                                                         abs=2 * e**7)


def test_peale_obliquity_is_the_small_angle_balance():
    """For small eps Peale's equation is alpha eps = |Omega'| (sin i + eps cos i): eps = |k'|/(alpha_0 - |k'| cot i),
    to the eps^2 terms (1e-7 relative); for Mercury's ~0.59"/yr it is the radar's 2' (from which C/MR^2 was read)."""
    n, e, speed, i = 2 * math.pi / 87.969, 0.2056, 0.59 * arcsec / 365.25, math.radians(8.6)
    alpha0 = precession_constant(n, e, mercury.J2, mercury.C22, mercury.C_MR2)
    eps = peale_obliquity(n, e, mercury.J2, mercury.C22, mercury.C_MR2, speed, i)
    assert eps == pytest.approx(speed / (alpha0 - speed / math.tan(i)), rel=1e-5)
    assert abs(eps - mercury.OBLIQUITY_ARCMIN[0] * ARCMIN) < mercury.OBLIQUITY_ARCMIN[1] * ARCMIN


def test_libration_within_the_radars_and_the_altimeters_one_sigma(run):
    amplitude = run["comparison"]["libration_amplitude_arcsec"]
    assert abs(amplitude - mercury.LIBRATION_AMPLITUDE_ARCSEC[0]) <= mercury.LIBRATION_AMPLITUDE_ARCSEC[1]
    assert abs(amplitude - mercury.STARK_2015["libration_arcsec"][0]) <= mercury.STARK_2015["libration_arcsec"][1]


def test_libration_is_the_closed_form_of_the_mantle(run):
    """(3/2)(B - A)/C_m (1 - 11e^2 + 959e^4/48), recomputed here from the body's constants and Mercury's mean
    eccentricity (0.205636, Simon et al. 1994), within 1 % (its e^6 remainder, 0.13 %; the core's friction, 0.2 %
    at a 1-yr coupling; the planets' perturbations)."""
    e = 0.205636
    closed = 1.5 * 4 * mercury.C22 / (mercury.C_MR2 * mercury.C_MANTLE_OVER_C) * (1 - 11 * e**2 + 959 * e**4 / 48)
    assert run["comparison"]["libration_amplitude_arcsec"] * arcsec == pytest.approx(closed, rel=0.01)


def test_obliquity_within_the_radars_and_the_altimeters_one_sigma(run):
    obliquity = run["comparison"]["obliquity_arcmin"]
    assert abs(obliquity - mercury.OBLIQUITY_ARCMIN[0]) <= mercury.OBLIQUITY_ARCMIN[1]
    assert abs(obliquity - mercury.STARK_2015["obliquity_arcmin"][0]) <= mercury.STARK_2015["obliquity_arcmin"][1]


def test_obliquity_follows_peales_equation_as_the_precession_is_scaled(run):
    """No precession, no obliquity; twice the precession, twice the obliquity, within 3" of Peale's equation (the
    normal's periodic wobbles, the core's lag); the turned orbit's normal moves at the scaled speed."""
    rows = {row["scale"]: row for row in run["precession"]}
    assert rows[0.0]["obliquity_arcmin"] * ARCMIN < 0.1 * arcsec
    assert rows[2.0]["orbit_normal_speed_arcsec_per_yr"] == pytest.approx(
        2 * run["comparison"]["orbit_normal_speed_arcsec_per_yr"], rel=1e-3)
    for row in [*rows.values(), {**run["comparison"]}]:
        assert abs(row["obliquity_arcmin"] - row["obliquity_peale_arcmin"]) * ARCMIN < 3 * arcsec


def test_a_start_away_from_the_state_settles_to_the_same_state(run):
    """Started 20" beyond Peale's state, the spin circles the same centre (within 1.5": the velocity fit's
    sensitivity to the normal's wobbles), 20" from its start."""
    other = run_scenario("scenarios/mercury_spin.toml", [*SPAN, "precession.scales=[]",
                                                         'start.obliquity_offset="20 arcsec"']).summary["comparison"]
    assert abs(other["obliquity_arcmin"] - run["comparison"]["obliquity_arcmin"]) * ARCMIN < 1.5 * arcsec
    assert other["free_precession_arcsec"] == pytest.approx(20, abs=2)


def test_bad_scales_are_refused_in_one_line():
    from spinorbit.base.errors import ScenarioError

    with pytest.raises(ScenarioError, match="precession.scales") as info:
        run_scenario("scenarios/mercury_spin.toml", ["precession.scales=[-1]"])
    assert "\n" not in str(info.value)
