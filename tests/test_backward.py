"""Backward runs: a span that ends before it starts.  The DE lunar integrations run both ways from their
epoch; the Moon scene does too, and is held to the same DE421 tolerances as forward.  Scenes that cannot
run backward refuse in one line naming span.end."""
from pathlib import Path

import pytest

from spinorbit.errors import ScenarioError
from spinorbit.runner import run_scenario
from spinorbit.scenarios import load_scenario

SCENARIOS = Path(__file__).parent.parent / "scenarios"


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


def test_forward_only_scene_refuses_a_backward_span():
    with pytest.raises(ScenarioError, match="span.end.*forward only.*moon_libration"):
        load_scenario(SCENARIOS / "free_body.toml", ["span.end=1999-01-01T00:00:00"])
