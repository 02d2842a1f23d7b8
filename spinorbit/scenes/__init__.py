"""Scene kinds: ``scene.kind`` in a scenario names a module of this folder, which declares it.

Each scene module defines ``SCENE`` (a spinorbit.scene.declaration.Scene: its keys, model, comparison, verdict, cost);
the runner (spinorbit.edge.runner) does the rest.  The kinds are the folder's modules (``common`` holds what they
share), found without importing them: a new scene is one file here, and a scenario loads only the scene it
names.
"""
import pkgutil
from importlib import import_module

from ..base.errors import ScenarioError

SHARED = ("common",)          # modules of this folder that are not scenes
SCENES = tuple(sorted(module.name for module in pkgutil.iter_modules(__path__)
                      if module.name not in SHARED and not module.name.startswith("_")))


def scene_module(kind):
    """The module for a scene kind; ScenarioError listing the kinds otherwise."""
    if kind not in SCENES:
        raise ScenarioError("scene.kind", kind, f"one of {list(SCENES)}")
    return import_module(f"{__name__}.{kind}")


def scene_of(kind):
    """The Scene a kind declares."""
    return scene_module(kind).SCENE


def stored_kinds():
    """{kind: Stored} of the kinds kept as a continuous solution (their Scene's ``stored``; imports every
    scene)."""
    return {kind: scene_of(kind).stored for kind in SCENES if scene_of(kind).stored is not None}
