"""Models as data: a System of bodies (figure, rotator), how they move, and what acts between them.

From that data a System derives its state layout, its parameter record and its compiled right-hand side
(spinorbit.models.system); the assemblies (spinorbit.models.assemblies) write every model the scenes use.
"""
import importlib

_HOMES = {"Barycentric": "barycentric", "Body": "figure", "Field": "figure", "Figure": "figure",
          "Centred": "motion", "Pair": "motion", "Distortion": "rotators", "Fixed": "rotators",
          "Gyroscopic": "rotators", "MantleCore": "rotators", "Rigid": "rotators", "System": "system"}

__all__ = ["Barycentric", "Body", "Centred", "Distortion", "Field", "Figure", "Fixed", "Gyroscopic", "Layout",
           "MantleCore", "Pair", "Rigid", "System"]


def __getattr__(name):
    """Each name from its module when first asked for (numba, which the models' kernels need, is imported then):
    a module that reads only data of the models (an assembly's levels) does not import it."""
    if name == "Layout":
        from ..base.layout import Layout

        return Layout
    if name in _HOMES:
        return getattr(importlib.import_module(f".{_HOMES[name]}", __name__), name)
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
