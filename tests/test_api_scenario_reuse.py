"""The API loads a built-in scene once per process when a call's values are the scene's own, and loads its own
scenario for any other value (the validated scene stays what ``expected`` judges by)."""
import pytest

from spinorbit import api, scenarios
from spinorbit.errors import ScenarioError


def test_the_validated_scene_is_reused_only_for_its_own_values(monkeypatch):
    loads = []
    load = scenarios.load_scenario
    monkeypatch.setattr(scenarios, "load_scenario", lambda *a, **k: loads.append((a, k)) or load(*a, **k))
    api._validated.cache_clear()
    own = api._scenario("moon_libration", {"orbit.source": "de421", "model.level": 3})
    assert api._scenario("moon_libration", {"orbit.source": "de421", "model.level": 3}) is own
    assert own["model.level"] == 3 and own["orbit.source"] == "de421" and len(loads) == 1
    other = api._scenario("moon_libration", {"orbit.source": "de421", "model.level": 2})
    assert other["model.level"] == 2 and len(loads) == 2
    with pytest.raises(ScenarioError, match="model.level"):      # True == 1 but is no level: loaded, and refused
        api._scenario("moon_libration", {"model.level": True})
    api.expected.cache_clear()
    assert api.expected("moon")["pole_arcsec"] == 0.1 and len(loads) == 3      # level 3's target, no load more
