"""Integrator registry: method name -> class, imported only when asked for."""
from importlib import import_module

from ..base.errors import InputError
from .base import Integrator

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
