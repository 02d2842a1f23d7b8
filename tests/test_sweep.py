"""Parameter sweeps on Dask: every member runs, writes its own directory, and is collected."""
import json
from pathlib import Path

import pytest

from spinorbit.sweep import members, parse_vary, run_sweep

FREE_BODY = Path(__file__).parents[1] / "scenarios" / "free_body.toml"


def test_vary_parsing_keeps_lists_and_quantities():
    assert parse_vary('span.end="10 d","20 d"') == ("span.end", ['"10 d"', '"20 d"'])
    key, values = parse_vary('body.omega0=["1 rad/d","0 rad/d","1 rad/d"],["2 rad/d","0 rad/d","1 rad/d"]')
    assert key == "body.omega0" and len(values) == 2 and values[0].startswith("[")
    assert len(members({"a": [1, 2, 3], "b": [4, 5]})) == 6


@pytest.mark.parametrize("scheduler", ["synchronous", "local"])
def test_sweep_over_tolerance_converges_to_the_closed_form(tmp_path, scheduler):
    grid = {"integrator.rtol": ["1e-7", "1e-12"]}
    records = run_sweep(FREE_BODY, grid, tmp_path, scheduler, ["span.end=50 d", "output.plots=false"])
    assert [r["status"] for r in records] == ["ok", "ok"]
    loose, tight = (r["omega_max_rel_error_vs_closed_form"] for r in records)
    assert tight < 1e-10 < loose < 1e-4
    assert json.loads((tmp_path / "sweep.json").read_text()) == records
    assert all((Path(r["out"]) / "summary.json").is_file() for r in records)


def test_a_key_given_twice_to_vary_is_refused_in_one_line(capsys):
    from spinorbit import cli
    from spinorbit.errors import ScenarioError
    from spinorbit.sweep import grid

    with pytest.raises(ScenarioError, match="--vary integrator.rtol") as info:
        grid(["integrator.rtol=1e-8", "span.end=5 d", "integrator.rtol=1e-10,1e-12"])
    assert "\n" not in str(info.value) and "once" in str(info.value)
    assert grid(["integrator.rtol=1e-8,1e-10", "span.end=5 d"]) == {"integrator.rtol": ["1e-8", "1e-10"],
                                                                      "span.end": ["5 d"]}
    assert cli.main(["sweep", "scenarios/free_body.toml", "--vary", "integrator.rtol=1e-8", "--vary",
                     "integrator.rtol=1e-10", "--scheduler", "synchronous", "--out", "/nonexistent/x"]) == 2
    assert capsys.readouterr().err.count("\n") == 1
