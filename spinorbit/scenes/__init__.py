"""Scene kinds: ``scene.kind`` in a scenario -> the module that builds and compares it.

Each scene module defines ``SCHEMA`` (its scenario keys, see scenarios.Key) and
``run(scenario) -> RunResult``.  Modules are imported only when a scenario
names them, so a scene loads nothing it does not use.
"""
from importlib import import_module

from ..errors import ScenarioError

SCENES = {
    "free_body": "spinorbit.scenes.free_body",
}


def scene_module(kind):
    """The module for a scene kind; ScenarioError listing the kinds otherwise."""
    if kind not in SCENES:
        raise ScenarioError("scene.kind", kind, f"one of {sorted(SCENES)}")
    return import_module(SCENES[kind])
