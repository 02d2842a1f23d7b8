"""The integrator contract and the solution it returns.

Contract for subclass authors (numbered so reviews can point at it):

1. Class attributes: ``name`` (registry key), ``order`` (global order of
   accuracy, or None for adaptive methods whose order is not the point),
   ``kind`` ("adaptive", "fixed", "structure-preserving", "averaged") and
   ``options`` (accepted option name -> :class:`~spinorbit.integrators.options.Option`, declared once with
   the method's default, unit, range and how a more accurate run sets it).
2. ``__init__(**options)`` accepts only the names in ``options``; anything else
   raises InputError naming the option and the accepted names.  ``refined(options)`` gives the options of a
   markedly more accurate run (the error estimate's); ``ladder(time_scale, spacing)`` the settings, coarse to
   fine, of the method's work-precision ladder (``spinorbit bench``).
3. ``solve(system, t_out)`` integrates a System (spinorbit.models: ``rhs``,
   ``params``, ``t0``, ``y0`` and the state's ``layout``) from ``system.t0`` and
   returns a :class:`Trajectory` holding the state at every time in ``t_out``
   (running away from ``system.t0`` in one direction: ascending for a forward
   run, descending for a backward one), every quaternion slice of the layout
   renormalised.
4. ``supports(system)`` says whether the method can run this system (e.g. a
   splitting method needs ``system.torque``); ``solve`` raises InputError
   otherwise.
5. Failure (NaN, step-size underflow, max steps) raises IntegrationError with
   the time and state, advice, and ``.partial`` = the Trajectory up to there.
6. ``nfev`` counts right-hand-side (or torque) evaluations, ``nsteps`` the steps (None where the
   method does not report them: scipy's solve_ivp); ``wall_s`` is the
   wall time of the solve excluding one-off compilation (warm up first).
7. A method that compiles the equations itself (``taylor``) reads ``system.expressions()`` (heyoka
   variables and derivatives) and ``system.traceable`` instead of ``rhs``.
8. Hooks, set on the instance before ``solve``: ``label`` names its progress bar (None: no bar);
   ``checkpoint`` (spinorbit.edge.checkpoint.Checkpoint or None) is offered the outputs so far between
   compiled chunks and resumes from them, by the methods whose ``resumable`` is True.
"""
from dataclasses import dataclass, field

import numpy as np

from ..base.errors import InputError, IntegrationError


@dataclass
class Trajectory:
    """States at output times: t (n,) in the system's time unit, y (n, dim) laid out by ``layout``."""

    t: np.ndarray
    y: np.ndarray
    method: str
    nfev: int = 0
    nsteps: int | None = 0      # None where the method does not report it (scipy's solve_ivp)
    wall_s: float = 0.0
    options: dict = field(default_factory=dict)
    layout: object = None

    def part(self, name):
        """The states' slice ``name`` (e.g. "moon.q"), (n, size)."""
        return self.y[:, self.layout[name]]

    @property
    def quaternion(self):
        """The first body's attitude quaternions (n, 4)."""
        return self.y[:, self.layout.quaternions[0]]

    @property
    def omega(self):
        """The first body's angular velocities, body axes (n, 3)."""
        body = next(s.name.split(".")[0] for s in self.layout.slices if s.kind == "quaternion")
        return self.part(f"{body}.omega")


class Integrator:
    name = "base"
    order = None
    kind = "adaptive"
    options: dict = {}
    resumable = False
    checkpoint = None
    LADDER_LENGTH = 14          # steps of a fixed-step method's work-precision ladder

    def __init__(self, **options):
        unknown = sorted(set(options) - set(self.options))
        if unknown:
            raise InputError(unknown[0], options[unknown[0]],
                                f"one of {sorted(self.options)} for method '{self.name}'")
        self.settings = {**self.defaults(), **options}
        self.label = self.name                 # of its progress bar; None: no bar

    @classmethod
    def defaults(cls):
        """{option: the method's default}."""
        return {name: option.default for name, option in cls.options.items()}

    @classmethod
    def refined(cls, options):
        """The settings (defaults filled in) of a run markedly more accurate than ``options``: each option as
        its declaration refines it (a step halved, tolerances divided by 100 down to the library's floor)."""
        settings = {**cls.defaults(), **options}
        return {name: cls.options[name].refine(value) if cls.options[name].refine else value
                for name, value in settings.items()}

    @classmethod
    def ladder(cls, time_scale, spacing):
        """Settings of the work-precision ladder, coarse to fine: steps halving from a quarter of the motion's
        ``time_scale``; a method that lands on every output starts at most at the output ``spacing`` (None:
        one output), so that the step shown is the step taken."""
        h0 = time_scale / 4
        if getattr(cls, "DENSE", None) is None and spacing is not None:
            h0 = min(h0, spacing)
        return [{"step": h0 / 2**k} for k in range(cls.LADDER_LENGTH)]

    def supports(self, system):
        return True

    def solve(self, system, t_out):
        raise NotImplementedError

    def _check_times(self, system, t_out):
        t_out = np.asarray(t_out, dtype=float)
        ordered = t_out.ndim == 1 and t_out.size > 0 and np.all(np.isfinite(t_out))
        if ordered:
            steps = np.diff(np.concatenate([[system.t0], t_out]))
            ordered = np.all(steps >= 0) or np.all(steps <= 0)
        if not ordered:
            shape = "" if t_out.ndim == 1 else f" in {t_out.ndim} dimensions"
            raise InputError("t_out", f"{t_out.size} output times{shape}",
                             "a 1-d array of finite times running away from t0 in one direction (forward or backward)")
        if not self.supports(system):
            raise InputError("method", self.name,
                                f"a method that supports system '{system.name}' (this one needs a rigid body "
                                "with an external torque)")
        return np.ascontiguousarray(t_out)        # one compiled loop whatever the caller's layout


def output_chunks(n, count=200):
    """Consecutive slices of range(n), at most ``count`` of them: the pieces a loop resumes over."""
    edges = np.linspace(0, n, min(n, count) + 1).round().astype(int)
    return [slice(a, b) for a, b in zip(edges[:-1], edges[1:])]


def check_finite(y, t, method, partial=None):
    """Raise IntegrationError if the state has a NaN or infinity."""
    if not np.all(np.isfinite(y)):
        err = IntegrationError(f"{method}: state became non-finite", t, y,
                               "Reduce the step or tolerance, or check the scene for a close encounter.")
        err.partial = partial
        raise err


def normalised(system, y):
    """The states (n, dim) with every quaternion of the system's layout made unit."""
    return system.layout.normalise(y) if len(y) else np.array(y, dtype=float)
