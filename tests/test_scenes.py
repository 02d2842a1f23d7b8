"""Each idealised scene, run through its scenario file, agrees with its closed form (summary["comparison"])."""
import math
from pathlib import Path

import pytest

from spinorbit.edge.runner import run_scenario

SCENARIOS = Path(__file__).resolve().parent.parent / "scenarios"


def comparison(name, *overrides):
    return run_scenario(SCENARIOS / f"{name}.toml", ("output.plots=false", *overrides)).summary["comparison"]


def test_free_body_hlw_100_periods():
    c = comparison("free_body", "integrator.estimate_error=false")
    assert c["regime"] == "about_A"
    assert c["period_d"] == pytest.approx(10.7315, abs=1e-4)
    assert c["omega_max_rel_error_vs_closed_form"] < 1e-10
    assert c["attitude_max_error_vs_closed_form_rad"] < 1e-10


@pytest.mark.parametrize("name", ["p92_general", "p92_arc_ab"])
def test_p92_axis_and_rate(name):
    c = comparison(name)
    assert c["axis_error_arcsec"] < 1e-3 and c["rate_rel_error"] < 1e-9
    if name == "p92_arc_ab":
        assert c["axis_cos_gamma"] == pytest.approx(1.0, abs=1e-15)


@pytest.mark.parametrize("name, case", [("p93_equilibrium", "equilibrium"), ("p93_bounded", "bounded"),
                                        ("p93_separatrix", "separatrix"), ("p93_circulation", "circulation")])
def test_p93_cases(name, case):
    c = comparison(name)
    assert c["case"] == case
    if case == "separatrix":
        assert c["zeta_error_max_arcsec_below_80deg"] < 1e-3
        for deg in (30, 60, 80):
            # crossing times interpolated linearly on the 0.05 d output grid: about 2e-5 d
            assert c[f"time_to_{deg}deg_d"] == pytest.approx(c[f"time_to_{deg}deg_euler_d"], abs=5e-5)
    else:
        assert c["zeta_error_max_arcsec"] < 1e-3
    if case == "bounded":
        assert c["period_measured_d"] == pytest.approx(c["period_closed_form_d"], abs=5e-5)
        assert c["max_digression_measured_deg"] == pytest.approx(45.0, abs=1e-3)       # C = 0: 45 deg (§826)
    if case == "circulation":
        assert c["half_turn_time_measured_d"] == pytest.approx(c["half_turn_time_closed_form_d"], abs=5e-5)


def test_p94_forced_libration():
    c = comparison("p94_moonlike")
    assert c["amplitude_measured_arcsec"] == pytest.approx(c["amplitude_euler_arcsec"], rel=1e-3)
    assert c["zeta_error_second_order_max_arcsec"] < c["zeta_error_first_order_max_arcsec"] / 3
    assert c["zeta_error_second_order_rel"] < 3e-4                  # remainder O(alpha^3, alpha beta^2)


def test_p95_pole_motion():
    c = comparison("p95_symmetric")
    assert c["pole_shift_rel_error"] < 2e-3                         # O(gamma' t) over 0.002 d
    assert c["spin_rel_change"] < 1e-9                              # §841: d gamma' = 0


def test_p96_earthlike_precession():
    c = comparison("p96_earthlike", 'span.end="315 d"')
    assert not c["resonance_detected"]
    # Euler's N cos n is high by aa/cc - 1 = 1% (§841 drops the pole's free rotation in the body).
    assert c["precession_rate_euler_rel_error"] == pytest.approx(0.01, abs=2e-3)
    assert abs(c["precession_rate_gyroscopic_rel_error"]) < 2e-3
    assert c["za_2phi_half_range_measured_arcsec"] == pytest.approx(c["za_2phi_half_range_gyroscopic_arcsec"], rel=5e-3)
    assert c["xza_2phi_amplitude_measured_arcsec"] == pytest.approx(c["xza_2phi_amplitude_gyroscopic_arcsec"], rel=5e-3)


def test_p96_resonance_detected_and_secular_growth():
    c = comparison("p96_near_resonance")
    assert c["resonance_detected"] and "2 delta" in c["resonance_message"]
    assert abs(c["za_2phi_growth_rel_error"]) < 0.01
    assert math.isfinite(c["za_2phi_growth_measured_arcsec_per_d"])


# Stress scenes (scenarios/stress/*.toml): each passes or fails on a number it reports in summary.json,
# and a failing integration writes its partial output through the command line
# (tests/edge/test_cli.py).


STRESS = Path(__file__).parent.parent / "scenarios" / "stress"


def stress_comparison(name, *overrides):
    return run_scenario(STRESS / f"{name}.toml", overrides).summary["comparison"]


def test_separatrix_side_and_time_to_90deg():
    """C = n(1 -+ 1e-9): bounded vs circulating as §826 says, time to the top within 1e-4 of the closed form."""
    c = stress_comparison("separatrix")
    assert c["time_rel_error_max"] < 1e-4
    assert c["passed"]


def test_degenerate_bodies():
    c = stress_comparison("degenerate")
    assert c["sphere_torque_max"] == 0.0
    assert c["attitude_error_max_rad"] < 1e-9
    assert c["passed"]


def test_extreme_shapes():
    c = stress_comparison("shapes")
    assert c["attitude_error_max_rad"] < 1e-9
    assert c["passed"]


@pytest.mark.parametrize("where", ["at", "near"])
def test_p96_stress_resonance_detected_and_secular_growth(where):
    """eps = 2 delta (exactly, and 5e-4 off): detected; ZA 2phi growth within 1% of §849's singular solution."""
    c = stress_comparison(f"p96_{where}_resonance")
    assert c["resonance_detected"] is True
    assert abs(c["za_2phi_growth_rel_error"]) < 0.01


@pytest.mark.slow
def test_intermediate_axis_flip_period():
    """1000 flips of I = (0.3, 0.35, 0.4), omega0 = (0.1, 15, 0.1): period 12.335 d within 0.1%."""
    c = stress_comparison("flip")
    assert abs(c["period_closed_form_d"] - 12.335) < 0.001
    assert c["period_rel_error_max"] < 1e-3
    assert c["passed"]


@pytest.mark.slow
def test_long_run_invariants():
    """1e6 torque-free steps (the scene's 1e7 in benchmarks/RESULTS.md): the splitting keeps |L| to rounding
    (a random walk of ~eps sqrt(rotations) = 5e-13, bound 1e-11) and its energy error does not grow."""
    c = stress_comparison("long_run", "stress.steps=1000000")
    assert c["L_norm_rel_drift_max_splitting"] < 1e-11
    assert c["passed"]

def stress_summary(name, *overrides):
    return run_scenario(STRESS / f"{name}.toml", overrides).summary


# Stress scenes on eccentric and slow orbits (scenarios/stress/): Mercury's 3:2 libration, Hyperion's
# chaotic tumbling, a fast spinner on a slow orbit.  Each passes or fails on numbers in summary.json.


def test_mercury_88d_libration():
    """3:2 state, e = 0.2056, (B - A)/C = 2.03e-4: the fitted 88-d amplitude against the linear forced solution
    (1e-3) and Margot et al. 2007's e^4 series (1%); the radar value 35.8 +- 2" within its sigma."""
    c = stress_comparison("mercury_3_2")
    assert c["S1_quadrature"] == pytest.approx(1 - 11 * 0.2056**2 + 959 * 0.2056**4 / 48, rel=3e-3)   # e^6 remainder
    assert abs(c["libration_88d_rel_error_vs_linear"]) < 1e-3
    assert abs(c["libration_88d_rel_error_vs_series"]) < 1e-2
    assert abs(c["libration_88d_measured_arcsec"] - 35.8) < 2.0
    assert c["passed"]


def test_hyperion_lyapunov_measured():
    """e = 0.1: a regular orbit ((B - A)/C = 0.01, synchronous) decays like ln t/t to below 0.01/T; Hyperion's
    (B - A)/C = 0.26 start is chaotic: the mean exponent of an ensemble of 16 starts around it is the same over
    500 and 1000 periods (rk8) and with DOP853 within 4 standard errors of the ensemble (a finite-time exponent
    follows the rounding, so only its statistics can be compared across machines and methods); the planar model
    matches the 3-D body in the plane; the map has a chaotic zone."""
    c = stress_comparison("hyperion", "lyapunov.orbits=500", "map.grid=[12, 12]", "map.orbits=100")
    assert c["lyapunov_regular_per_T"] < 0.01
    assert c["lyapunov_regular_per_T"] < 2 * c["lyapunov_regular_ln_t_over_t_per_T"]
    assert c["lyapunov_regular_ratio_2T_over_T"] < 0.75
    for key in ("rk8_T", "rk8_2T", "dop853_T"):
        assert c[f"lyapunov_nominal_{key}_per_T"] > 0.2           # Lyapunov time of a few periods at most
    for pair in ("rk8_T_vs_rk8_2T", "rk8_T_vs_dop853_T"):
        assert c[f"lyapunov_nominal_{pair}_sigmas"] < 4.0
    assert c["lyapunov_3d_per_T"] > 0.2
    assert c["planar_vs_3d_theta_max_rad_5_orbits"] < 1e-8
    assert 0.3 < c["chaotic_fraction_of_map"] < 0.9
    assert c["passed"]


@pytest.mark.slow
def test_fast_spin_slow_orbit_integrators():
    """Spin/orbit = 1e5 over one orbit: the converged run's figure axis agrees with the best other run to 1e-9 rad;
    every full-span run's precession rate agrees with it to 1e-8 and with P96's N cos n cc/aa to 1e-3 (the closed
    form is first order in N/delta = 1e-3); the splittings reach 1e-9 rad in the figure axis at steps of 0.137 d.
    The suite runs four of the scene's ten integrator runs (the scipy ones, Python per step, take minutes)."""
    s = stress_summary("fast_spin", 'stress.runs=[{method = "rk8", step = 0.125}, {method = "strang", step = 0.137}, '
                             '{method = "yoshida4", step = 0.137}, {method = "suzuki4", step = 0.137}]')
    c, runs = s["comparison"], {r["run"]: r for r in s["details"]["runs"]}
    assert c["reference_agreement_axis_rad"] < 1e-9
    assert abs(c["precession_rate_reference_rel_error"]) < 1e-3
    for r in runs.values():
        if r["span_d"] == 100000.0:
            assert abs(r["precession_rate_rel_diff_vs_converged"]) < 1e-8
            assert abs(r["precession_rate_rel_error"]) < 1e-3
    for name in ("strang step=0.137", "suzuki4 step=0.137", "yoshida4 step=0.137"):
        assert runs[name]["axis_error_vs_converged_rad"] < 1e-9
    assert c["passed"]
