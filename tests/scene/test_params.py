"""A loaded scenario's typed parameters hold what its keys name (spinorbit.scene.params, ``Key.parse``): an orbit source
as its OrbitSource, the name the file gives; a name that names nothing is refused at load, in one line; the same
record from --set text and from Python values, frozen; a value in the wrong unit refused naming its key."""
import dataclasses
import tomllib
from pathlib import Path

import astropy.units as u
import numpy as np
import pytest

from spinorbit.base.errors import ScenarioError
from spinorbit.edge.cli import main
from spinorbit.edge.scenarios import load_scenario
from spinorbit.orbits.sources import OrbitSource

SCENARIOS = Path(__file__).parents[2] / "scenarios"


@pytest.mark.parametrize("name", ["moon_libration", "moon_libration_rebound", "earth_moon_coupled_rebound",
                                  "earth_precession_nutation_circular", "mars_orientation"])
def test_a_loaded_orbit_source_is_the_source_the_file_names(name):
    path = SCENARIOS / f"{name}.toml"
    written = tomllib.loads(path.read_text())
    p = load_scenario(path).params
    assert isinstance(p.orbit.source, OrbitSource)
    assert p.orbit.source.name == written["orbit"]["source"]
    compared = written.get("compare", {}).get("source")
    if compared is not None:
        assert isinstance(p.compare.source, OrbitSource) and p.compare.source.name == compared


def test_an_absent_source_is_the_keys_default():
    """No [compare] source: None; no [orbit] source (mercury_spin.toml): DE421, the ephemeris with the Moon's
    angles."""
    assert "orbit" not in tomllib.loads((SCENARIOS / "mercury_spin.toml").read_text())
    p = load_scenario(SCENARIOS / "moon_libration.toml", ['span.end="4 d"']).params
    assert p.compare.source is None
    default = load_scenario(SCENARIOS / "mercury_spin.toml").params.orbit.source
    assert default.name == "de421" and default.lunar_angles


@pytest.mark.parametrize("key, given, says", [
    ("orbit.source", "de42", "or an installed naif-de42 package"),
    ("orbit.source", "no_such_kernel.bsp", "(no such file)"),
    ("orbit.source", "", "'rebound'"),
    ("orbit.source", "x" * 300, "File name too long"),
    ("compare.source", "de42", "or an installed naif-de42 package"),
])
def test_a_source_that_names_nothing_is_refused_at_load_in_one_line(key, given, says):
    with pytest.raises(ScenarioError) as info:
        load_scenario(SCENARIOS / "moon_libration.toml", [f'{key}="{given}"'])
    message = str(info.value)
    assert message.startswith(f"{key}: got '{given[:40]}") and "; expected " in message
    assert says in message and "\n" not in message


def test_the_command_line_refuses_an_unknown_source_before_it_runs(tmp_path, capsys):
    code = main(["run", str(SCENARIOS / "moon_libration.toml"), "--out", str(tmp_path / "out"),
                 "--set", 'orbit.source="de42"'])
    err = capsys.readouterr().err
    assert code == 2 and len(err.splitlines()) == 1 and err.startswith("error: orbit.source: got 'de42'"), err
    assert not (tmp_path / "out").exists()


def test_the_typed_record_is_the_same_from_set_text_and_from_python_values():
    by_text = load_scenario("free_body", ['span.step="6 h"', 'body.omega0=["0.1 rad/d", "2 rad/d", "0.1 rad/d"]'])
    by_value = load_scenario("free_body", values={"span.step": 6 * u.h, "body.omega0": [0.1, 2, 0.1] * u.rad / u.d})
    for p in (by_text.params, by_value.params):
        assert p.span.step == 0.25                          # 6 h in days, exactly
        assert isinstance(p.body.moments, np.ndarray) and p.body.moments.shape == (3,)
        assert p.body.omega0 is p.body.omega0
        assert p.integrator.method == "dop853" and p.span.end > p.span.start
    assert np.array_equal(by_text.params.body.omega0, by_value.params.body.omega0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        by_value.params.body.omega0 = np.zeros(3)


def test_a_python_value_in_the_wrong_unit_is_refused_in_one_line_naming_the_key():
    with pytest.raises(ScenarioError) as info:
        load_scenario("free_body", values={"span.step": 3 * u.km})
    message = str(info.value)
    assert message.startswith("span.step:") and "3.0 km" in message and "'d'" in message and "\n" not in message


def test_the_moons_start_is_held_in_tdb_days():
    """model.start = 2000-12-01T00:00 TDB is JD 2451879.5 TDB: 334.5 days after J2000.0 (JD 2451545.0); absent,
    None (the span's start); a text that is no date is refused at load in one line."""
    path = SCENARIOS / "moon_libration.toml"
    assert load_scenario(path, ["model.start=2000-12-01T00:00:00"]).params.model.start == 334.5
    assert load_scenario(path).params.model.start is None
    with pytest.raises(ScenarioError) as info:
        load_scenario(path, ['model.start="next tuesday"'])
    assert str(info.value).startswith("model.start: got 'next tuesday'; expected an ISO date in TDB")


def test_a_scene_run_from_python_with_its_parameters_replaced_is_the_run_the_text_asks_for():
    """The Python way (README): the built-in scene's parameters with the span and the tolerance replaced
    (dataclasses.replace, Scenario.with_params) run to the states --set text gives, which Euler's closed form
    passes; a replaced value is checked as a file's is (the method's options)."""
    from spinorbit import run_scenario
    from spinorbit.scene.params import converted

    scenario = load_scenario("free_body")
    p = scenario.params
    span = dataclasses.replace(p.span, end=p.span.start + 5.0, step=converted(type(p), "span.step", 6 * u.h))
    typed = dataclasses.replace(p, span=span, integrator=dataclasses.replace(p.integrator, rtol=1e-12))
    by_python = run_scenario(scenario.with_params(typed))
    by_text = run_scenario("free_body", ['span.end="5 d"', 'span.step="6 h"', "integrator.rtol=1e-12"])
    assert span.step == 0.25 and by_python.summary["verdict"]["result"] == "pass"
    assert by_python.summary["comparison"] == by_text.summary["comparison"]
    assert by_python.table.colnames == by_text.table.colnames and len(by_python.table) == 21
    assert all(np.array_equal(by_python.table[name], by_text.table[name]) for name in by_text.table.colnames)
    with pytest.raises(ScenarioError, match="integrator.rtol"):
        scenario.with_params(dataclasses.replace(p, integrator=dataclasses.replace(p.integrator, rtol=1.0)))
    with pytest.raises(ScenarioError, match="span.step"):
        converted(type(p), "span.step", 3 * u.km)


def test_the_integrator_table_declares_every_option_the_methods_know():
    """IntegratorTable's option fields are spinorbit.integrators.options.OPTIONS, no more, no fewer: an option a
    method accepts but the table lacked could not be loaded."""
    from spinorbit.integrators.options import OPTIONS
    from spinorbit.scene.params import IntegratorTable

    declared = {f.name for f in dataclasses.fields(IntegratorTable)} - {"method", "estimate_error"}
    assert declared == set(OPTIONS)


def test_replaced_parameters_are_refused_a_span_the_scene_cannot_run_as_a_file_is():
    """A backward span for a scene that runs forward only, and a span under a microday, are refused in one line
    on span.end whether the file gives them or Python replaces them (Scenario.with_params)."""
    scenario = load_scenario("free_body")
    p = scenario.params
    for end in (p.span.start - 10.0, p.span.start + 1e-8):
        with pytest.raises(ScenarioError) as info:
            scenario.with_params(p.with_span(end=end))
        assert str(info.value).startswith("span.end:") and "\n" not in str(info.value)
    with pytest.raises(ScenarioError, match="runs forward only"):
        load_scenario("free_body", ["span.end=-10 d"])
