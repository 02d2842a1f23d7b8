"""Integrator registry: method name -> class, imported only when asked for.

``get_method("dop853")`` or ``get_method(MyIntegrator)`` returns the class;
``integrate(system, t_out, "rk8", step=0.5)`` solves.  See base.py for the
contract every method follows.
"""
from importlib import import_module

from ..errors import InputError
from .base import Integrator, Solution

METHODS = {
    "dop853": "spinorbit.integrators.scipy_ivp:DOP853",
    "radau": "spinorbit.integrators.scipy_ivp:Radau",
    "rk45": "spinorbit.integrators.scipy_ivp:RK45",
    "rk8": "spinorbit.integrators.rk8:RK8",
    "rk4": "spinorbit.integrators.rk4:RK4",
    "strang": "spinorbit.integrators.splitting:Strang",
    "yoshida4": "spinorbit.integrators.splitting:Yoshida4",
    "suzuki4": "spinorbit.integrators.splitting:Suzuki4",
    "taylor": "spinorbit.integrators.taylor:Taylor",
}


def get_method(method):
    """The integrator class for a registry name or an Integrator subclass."""
    if isinstance(method, type) and issubclass(method, Integrator):
        return method
    if method not in METHODS:
        raise InputError("method", method, f"one of {sorted(METHODS)}")
    module, cls = METHODS[method].split(":")
    return getattr(import_module(module), cls)


def integrate(system, t_out, method="dop853", **options):
    """Integrate ``system`` to the output times with the named method and options."""
    return get_method(method)(**options).solve(system, t_out)


__all__ = ["METHODS", "Integrator", "Solution", "get_method", "integrate"]
