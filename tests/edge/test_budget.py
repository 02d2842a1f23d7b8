"""The up-front estimate counts the N-body stage a run does before its own integration: the deep-time orbital
solution's WHFast steps (none once it is cached) and REBOUND's IAS15 days for orbit.source = 'rebound'.

The references are closed forms: the steps a span of S days at the orbit's step h asks for (S / h), the days
REBOUND integrates out from DE421's nearest date to the span and over it, times the measured costs."""
import subprocess
import sys
from pathlib import Path

import pytest

from spinorbit.base.errors import ScenarioError
from spinorbit.edge.scenarios import load_scenario
from spinorbit.orbits import solution
from spinorbit.scene.declaration import NBODY_COSTS

ROOT = Path(__file__).parents[2]
YEAR_D = 365.25
MYR_D = 1e6 * YEAR_D


def test_a_deep_time_run_of_hours_is_refused_with_the_estimate(tmp_path):
    with pytest.raises(ScenarioError) as info:
        load_scenario("earth_deep_time", ['span.end="-20 Myr"', 'limits.time="60 s"',
                                          f"orbit.file={tmp_path / 'none.npz'}"])
    steps = 20 * MYR_D / 5.0
    text = str(info.value)
    assert text.startswith("span.end: got '-20 Myr'") and f"{steps:,.0f} WHFast steps" in text
    assert f"~{steps * NBODY_COSTS['WHFast steps'] / 3600:.3g} h" in text and "\n" not in text


def test_the_command_line_refuses_100_myr_without_starting(tmp_path):
    done = subprocess.run([sys.executable, "-m", "spinorbit.edge.cli", "--quiet", "run", "earth_deep_time", "--set",
                           'span.end="-100 Myr"', "--set", f"orbit.file={tmp_path / 'none.npz'}", "--out",
                           str(tmp_path / "out")], capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert done.returncode == 2 and done.stderr.count("\n") == 1 and "WHFast steps" in done.stderr
    assert not (tmp_path / "none.npz").exists()


def test_a_cached_solution_is_not_counted_again(tmp_path):
    settings = solution.Settings()
    path = tmp_path / "a.npz"
    solution.solve(settings, -200 * YEAR_D, 0.0, path=path)
    assert solution.steps_to_compute(settings, 0.0, -200 * YEAR_D, path) == 0
    assert solution.steps_to_compute(settings, 0.0, -300 * YEAR_D, path) == pytest.approx(100 * YEAR_D / 5.0,
                                                                                          rel=1e-12)
    assert solution.steps_to_compute(settings, 0.0, -300 * YEAR_D, tmp_path / "none.npz") == \
        pytest.approx(300 * YEAR_D / 5.0, rel=1e-12)
    scenario = load_scenario("earth_deep_time", ['span.end="-200 yr"', f"orbit.file={path}",
                                                 'span.step="100 yr"', 'integrator.step="10 yr"'])
    # the solution reaches 2 kyr at least (ERFA's comparison): 1800 yr beyond the file's 200
    assert scenario.counts()["WHFast steps"] == pytest.approx(1800 * YEAR_D / 5.0, rel=1e-12)


def test_a_rebound_orbit_far_from_de421_counts_the_days_out():
    from spinorbit.orbits.kernel import DE421Arrays

    scenario = load_scenario("moon_libration_rebound", ['span.start="2400-01-01T12:00:00"', 'span.end="30 d"'])
    out = scenario.params.span.start - DE421Arrays().span[1]
    assert scenario.counts()["IAS15 days"] == pytest.approx(out + 30.0, rel=1e-12)
    with pytest.raises(ScenarioError) as info:
        load_scenario("moon_libration_rebound", ['span.start="2400-01-01T12:00:00"', 'span.end="30 d"',
                                                 'limits.time="30 s"'])
    assert str(info.value).startswith("orbit.source: got 'rebound'") and "IAS15 days" in str(info.value)


def test_the_solar_system_counts_the_days_its_taylor_run_follows():
    """1950-01-01 (JD 2433282.5) to 4969-06-28 contains DE421's epoch (1969-06-28), from which the run goes both
    ways: the Taylor integrator follows the whole span, twice with the error estimated; refused under a
    one-minute limit on span.end, in one line, with the count and the estimate."""
    from astropy.time import Time

    end_jd = Time("4969-06-28", scale="tdb").jd
    with pytest.raises(ScenarioError) as info:
        load_scenario("solar_system", ["span.end=4969-06-28", 'limits.time="1 min"',
                                       "integrator.estimate_error=true"])
    text = str(info.value)
    assert text.startswith("span.end: got '4969-06-28'") and "\n" not in text
    counted = float(text.split(" Taylor days")[0].rsplit(" ", 1)[1].replace(",", ""))
    assert counted == pytest.approx(2 * (end_jd - 2433282.5), abs=2)


def test_the_solar_system_estimate_is_its_days_times_the_measured_cost():
    from spinorbit.edge import budget

    scenario = load_scenario("solar_system")                     # 1950-2050, Taylor, no error estimate
    days = 2469807.5 - 2433282.5                                   # 2050-01-01 less 1950-01-01, JD TDB
    cost = NBODY_COSTS["Taylor days (solar system)"]
    assert budget.estimate(scenario)["time_s"] == pytest.approx(days * cost, rel=1e-9)
