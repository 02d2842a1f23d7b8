"""Integrators, and the one door to them: ``simulate(system, t_out, "rk8", {"step": 0.5})``.

``METHODS`` (registry.py) names the methods, ``get_method`` gives a class; each class declares its options once
(options.py) and follows the contract in base.py.  Nothing outside this package calls a method's ``solve``:
:func:`simulate` (simulation.py) does, for the scenes, the models' starts, the ladders and the Lyapunov flows.
"""
from .base import Integrator, Trajectory
from .registry import METHODS, get_method

__all__ = ["METHODS", "Integrator", "Trajectory", "get_method", "simulate"]


def __getattr__(name):
    """``simulate`` imported when first asked for: the package's options and registry stay free of numba."""
    if name == "simulate":
        from .simulation import simulate

        return simulate
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
