"""A method named on the command line over a scene file written for another (spinorbit.edge.method_switch): the file's
options the new method takes are carried over, the others dropped and said, and an option typed with the switch is
never touched."""
import json

import pytest

from spinorbit.base.errors import ScenarioError
from spinorbit.edge.cli import main
from spinorbit.edge.scenarios import load_scenario, taylor_kinds

TAYLOR_SCENES = ("free_body", "p92_arc_ab", "p93_bounded", "p94_moonlike", "p95_symmetric", "p96_earthlike",
                 "solar_system", "stress/coupled_conservation")


def test_every_kind_taylor_takes_has_a_scene_here():
    kinds = {load_scenario(name).kind for name in TAYLOR_SCENES}
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
