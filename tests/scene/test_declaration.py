"""The scene protocol (spinorbit.scene.declaration): one runner that builds a scene's model once; what a scene
declares is read from its Scene, not restated above it (its typed parameters: tests/scene/test_params.py)."""
import dataclasses

import pytest

from spinorbit.base.errors import ScenarioError
from spinorbit.edge import api
from spinorbit.edge.scenarios import load_scenario
from spinorbit.scenes import SCENES, scene_module, scene_of


def test_every_scene_declares_a_scene_the_one_runner_runs():
    for kind in SCENES:
        module = scene_module(kind)
        scene = module.SCENE
        assert scene.schema and scene.verdict is not None, kind
        assert scene.build is not None and scene.compare is not None, kind
        assert not hasattr(module, "run"), kind        # no pipeline of its own


def test_the_runner_builds_a_scene_model_once(monkeypatch):
    from spinorbit.edge.runner import run_scenario

    scene = scene_of("free_body")
    calls = []

    def counted(p, times):
        calls.append(times.size)
        return scene.build(p, times)

    monkeypatch.setattr("spinorbit.scenes.free_body.SCENE", dataclasses.replace(scene, build=counted))
    result = run_scenario("free_body", ['span.end="5 d"'])
    assert calls == [result.table["time"].size]
    assert result.summary["verdict"]["result"] == "pass"


def test_the_apis_tolerances_are_the_validated_scenes_verdicts():
    """Each answer a scene declares (scene.Answer) is answered from a validated scenario of that scene, and
    states its verdict's tolerances; the bodies spinorbit.orientation answers for are the answers' bodies."""
    for kind in SCENES:
        for answer in scene_of(kind).answers:
            scenario = load_scenario(answer.scenario)
            assert scenario.kind == kind
            checks = {c.metric: c.tolerance for c in scenario.scene.verdict_for(scenario.params, {}).checks}
            assert {name: api.expected(answer.name)[name] for name in answer.tolerances} == \
                {name: checks[metric] for name, metric in answer.tolerances.items()}
    assert api.bodies() == ("earth", "mars", "moon")
    assert api.expected("moon")["pole_arcsec"] == 0.1        # level 3 against DE421 (moon_libration.TOLERANCES)


def test_a_scenes_cost_and_time_scales_come_from_its_scene():
    moon = load_scenario("moon_libration")
    assert moon.cost() is scene_of("moon_libration").cost and moon.cost().step_s == 2e-4
    with pytest.raises(ScenarioError) as info:            # the torque's time-scale sqrt(3 GM/s^3), declared
        load_scenario("p93_bounded", ['orbit.radius="1 km"'])
    assert str(info.value).startswith("orbit.radius:") and "sqrt(3 orbit.gm/orbit.radius^3)" in str(info.value)
