"""What a user types at the command line works or is answered in words that say what is accepted: a method
switched with --set over a file written for another, dates and durations, a value with a space left unquoted,
and `list` / `show` printing every word at any terminal width."""
import json

import pytest

from spinorbit.cli import main
from spinorbit.errors import ScenarioError
from spinorbit.scenarios import load_scenario, taylor_kinds

TAYLOR_SCENES = ("free_body", "p92_arc_ab", "p93_bounded", "p94_moonlike", "p95_symmetric", "p96_earthlike",
                 "solar_system", "stress/coupled_conservation")


def test_every_kind_taylor_takes_has_a_scene_here():
    kinds = {load_scenario(name)["scene.kind"] for name in TAYLOR_SCENES}
    assert kinds == set(taylor_kinds())


@pytest.mark.parametrize("scene", TAYLOR_SCENES)
def test_taylor_from_the_command_line_takes_the_files_tolerance_and_drops_what_it_cannot_use(scene):
    in_file = load_scenario(scene).data["integrator"]
    scenario = load_scenario(scene, ["integrator.method=taylor"])
    options = scenario.params.integrator.options()
    assert scenario.params.integrator.method == "taylor" and set(options) <= {"tolerance", "compact_mode", "opt_level"}
    if "rtol" in in_file:                                       # a relative tolerance stays one
        assert options["tolerance"] == in_file["rtol"]
    for name in set(in_file) - {"method", "estimate_error", "tolerance"}:
        assert any(note.startswith(f"integrator.{name} = ") for note in scenario.notes)


def test_a_method_switch_never_touches_an_option_typed_with_it():
    with pytest.raises(ScenarioError, match="integrator.rtol"):
        load_scenario("free_body", ["integrator.method=taylor", "integrator.rtol=1e-10"])


def test_a_tolerance_out_of_the_new_options_range_is_dropped_and_said():
    scenario = load_scenario("solar_system", ["integrator.method=dop853"])    # Taylor's 1e-15 < rtol's 100 eps
    assert "rtol" not in scenario.params.integrator.options()
    assert scenario.notes == ["integrator.tolerance = 1e-15 from the scene file dropped: method 'dop853' does "
                              "not take it (its default applies)"]


def test_free_body_on_taylor_from_the_command_line_runs_and_meets_eulers_closed_form(tmp_path, capsys):
    assert main(["--quiet", "run", "free_body", "--set", "integrator.method=taylor", "--set", "span.end=2 d",
                 "--out", str(tmp_path / "run")]) == 0
    err = capsys.readouterr().err
    assert "integrator.rtol = 1e-13 from the scene file taken as integrator.tolerance for method 'taylor'" in err
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    # Euler's closed form of the torque-free body (§808): the scene's own tolerance, 1e-10 rad
    assert summary["comparison"]["attitude_max_error_vs_closed_form_rad"] <= 1e-10


@pytest.mark.parametrize("end", ["2000-13-45", "2030-01-01T00:00:00 UTC", "yesterday", "3 fortnights ago"])
def test_a_bad_end_date_is_told_that_iso_dates_and_durations_are_accepted(end):
    with pytest.raises(ScenarioError) as err:
        load_scenario("free_body", [f"span.end={end}"])
    text = str(err.value)
    assert err.value.key == "span.end" and "an ISO date in TDB without a time zone" in text
    assert "a finite duration from span.start" in text and "'2 days'" in text


@pytest.mark.parametrize("end, days", [("2 days", 2.0), ("2 d", 2.0), ("3 weeks", 21.0), ("1 years", 365.25)])
def test_durations_in_plural_words_are_read(end, days):
    scenario = load_scenario("free_body", [f"span.end={end}"])
    assert scenario.params.span.end - scenario.params.span.start == pytest.approx(days, rel=1e-15)


def test_a_bad_start_date_says_iso_dates_in_tdb():
    with pytest.raises(ScenarioError, match="an ISO date in TDB without a time zone, e.g. '2000-01-01'"):
        load_scenario("free_body", ["span.start=yesterday"])


def test_a_value_with_a_space_left_unquoted_gets_a_hint_to_quote_it(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["run", "free_body", "--set", "span.step=2", "km"])
    assert stop.value.code == 2
    assert 'unrecognized arguments: km (a value with spaces needs quotes: --set "span.step=2 km")' in \
        capsys.readouterr().err


def words(text):
    return " ".join(text.split())


def test_list_prints_every_title_whole_at_any_width(monkeypatch, capsys):
    import tomllib

    from spinorbit import catalogue

    titles = [tomllib.loads(path.read_text())["scene"]["title"] for path in catalogue.folder().rglob("*.toml")]
    for columns in ("60", "200"):
        monkeypatch.setenv("COLUMNS", columns)
        assert main(["list"]) == 0
        out = capsys.readouterr().out
        assert all(words(title) in words(out) for title in titles)


def test_show_ends_the_scenes_sentence_and_prints_every_meaning_whole(monkeypatch, capsys):
    from spinorbit.key_table import key_table

    heading, rows = key_table("earth_deep_time")
    assert heading.endswith("gives it.")                          # the docstring's first paragraph, whole
    for columns in ("80", "200"):
        monkeypatch.setenv("COLUMNS", columns)
        assert main(["show", "earth_deep_time"]) == 0
        out = words(capsys.readouterr().out)
        assert words(heading) in out
        assert all(words(row[-1]) in out and row[0] in out for row in rows)
        title = "\"Earth's obliquity and precession, 1 Myr back, vs La2004\""         # the file's, wrapped in its cell
        assert all(word in out.split() for word in title.split())
