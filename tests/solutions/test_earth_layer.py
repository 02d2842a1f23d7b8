"""The Earth's answer at a date does not change when the store grows elsewhere (issue 44 item 7): the non-rigid
layer and the mean pole are fitted over fixed windows (the scene's span and its repeats), not over the stored span.
A two-year scene stands for the validated century (its windows are two years long), so the test runs in seconds."""
import numpy as np
import pytest

from spinorbit.edge.scenarios import load_scenario
from spinorbit.solutions import earth_layer, for_scenario, store
from tests.units import mas

SHORT = {"span.start": "2024-01-01", "span.end": "2026-01-01", "earth.hd": "iau2006", "earth.tides": "none",
         "orbit.planets": False}


@pytest.fixture
def place(tmp_path, monkeypatch):
    monkeypatch.setitem(store.PLACE, "directory", tmp_path)
    return tmp_path


def test_an_answer_in_the_first_window_is_the_same_after_the_store_reaches_the_next(place):
    """The layer at 50 dates of 2024-2025 from the rigid solution over the scene's window, then again once the
    rigid solution reaches through the next window: equal within 1e-3 µas (the fits over the first window are the
    same; only rounding of the vectorised arguments differs).  The code before the windows moved them by 270 mas."""
    scenario = load_scenario("earth_precession_nutation_nonrigid", values=SHORT)
    first, last = earth_layer.reach(scenario, scenario.params.span.start, scenario.params.span.start)
    t = np.linspace(first + 1.0, last - 1.0, 50)
    before = earth_layer.layer(for_scenario(scenario, first, last), scenario, True)
    _, further = earth_layer.reach(scenario, last + 300.0, last + 300.0)
    after = earth_layer.layer(for_scenario(scenario, first, further), scenario, True)
    assert after.span[1] > before.span[1] + 300.0
    assert len(after.provenance["fit_windows_tdb_d"]) == 2
    assert np.abs(after.components(t) - before.components(t)).max() <= 1e-6 * mas
