"""A value the span cannot support is null with its reason, never NaN; summary.json is strict JSON."""
import json
import math

from spinorbit.reports import write_run
from spinorbit.runner import mark_unmeasured, run_scenario
from spinorbit.theory import PlanarLibration, libration_n

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
