"""Scene kinds: ``scene.kind`` in a scenario -> the module that declares it.

Each scene module defines ``SCENE`` (a spinorbit.scene.Scene: its keys, model, comparison, verdict, cost);
the runner (spinorbit.runner) does the rest.  Modules are imported only when a scenario names them, so a
scene loads nothing it does not use.
"""
from importlib import import_module

from ..errors import ScenarioError

SCENES = {
    "free_body": "spinorbit.scenes.free_body",
    "earth_precession_nutation": "spinorbit.scenes.earth_precession_nutation",
    "moon_libration": "spinorbit.scenes.moon_libration",
    "p92_start_from_rest": "spinorbit.scenes.p92_start_from_rest",
    "p93_planar_libration": "spinorbit.scenes.p93_planar_libration",
    "p94_forced_libration": "spinorbit.scenes.p94_forced_libration",
    "p95_near_principal_axis": "spinorbit.scenes.p95_near_principal_axis",
    "p96_precession": "spinorbit.scenes.p96_precession",
    "stress_free_body": "spinorbit.scenes.stress_free_body",
    "stress_separatrix": "spinorbit.scenes.stress_separatrix",
    "stress_mercury": "spinorbit.scenes.stress_mercury",
    "mercury_spin": "spinorbit.scenes.mercury_spin",
    "stress_hyperion": "spinorbit.scenes.stress_hyperion",
    "stress_fast_spin": "spinorbit.scenes.stress_fast_spin",
    "coupled_conservation": "spinorbit.scenes.coupled_conservation",
    "earth_moon_coupled": "spinorbit.scenes.earth_moon_coupled",
    "solar_system": "spinorbit.scenes.solar_system",
    "earth_deep_time": "spinorbit.scenes.earth_deep_time",
    "mars_deep_time": "spinorbit.scenes.mars_deep_time",
    "earth_moon_history": "spinorbit.scenes.earth_moon_history",
    "mars_orientation": "spinorbit.scenes.mars_orientation",
}


def scene_module(kind):
    """The module for a scene kind; ScenarioError listing the kinds otherwise."""
    if kind not in SCENES:
        raise ScenarioError("scene.kind", kind, f"one of {sorted(SCENES)}")
    return import_module(SCENES[kind])


def scene_of(kind):
    """The Scene a kind declares."""
    return scene_module(kind).SCENE
