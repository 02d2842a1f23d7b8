"""Taylor's method with heyoka (Biscani & Izzo 2021, MNRAS 504, 2614): adaptive order and step, compiled by LLVM.

heyoka integrates a system of expressions, which a System gives as ``system.expressions()`` (its generated
right-hand side run on expressions: spinorbit.models.trace) -- so the method takes a System whose every term is
a function of the state and the time (bodies in the state, analytic orbits), and refuses one that reads an
ephemeris.  The option ``tolerance`` is heyoka's: the order is chosen from it and each step's size from the
Taylor coefficients' decay (Jorba & Zou 2005), so that the local error per step is about the tolerance relative
to the state (absolute below a state of order 1).

Compilation: in compact mode (the default for every System but a free body) heyoka writes each kind of term once
and loops over its instances, which compiles the closed Earth-Moon system in seconds where the unrolled code
takes minutes (and a body under one point mass in 0.4 s instead of 1.4 s), at about twice the run time.  The
compiled code is kept in heyoka's on-disk cache, under spinorbit's cache directory (spinorbit.base.linker), so that a
later process compiles nothing.

The outputs come from the Taylor polynomials of one propagation (heyoka's ``propagate_grid``: dense output, each
step's size from the state alone, only the step onto the last output shortened), so a trajectory does not depend
on when it is sampled: outputs every 2 d or every 3 d are one orbit at the days they share, to the polynomials'
rounding.  A propagation cut into pieces ending on outputs shortens a step at each cut and follows another
sequence of steps after it: that moved the solar system's Mercury by up to 3.4 m over the century
(benchmarks/RESULTS.md, with the double-precision floor that remains).  The progress bar advances from heyoka's
step callback.
"""
import copy
import functools
import os
import time

import numpy as np

from ..base.errors import InputError, IntegrationError
from ..base.progress import progress
from .base import Integrator, Trajectory, normalised
from .options import COMPACT_MODE, OPT_LEVEL, TOLERANCE


@functools.cache
def heyoka():
    """heyoka, its on-disk cache under spinorbit's cache directory (private to the user, like the kernels'; a
    directory of another user's, or one others may read or write, is not used: every build compiles)."""
    import heyoka as hy

    from ..base.linker.cache import kernels_dir

    path = kernels_dir().parent / "heyoka"
    path.mkdir(mode=0o700, exist_ok=True)
    status = path.stat()
    private = status.st_uid == os.getuid() and not status.st_mode & 0o077
    hy.llvm_state.set_diskcache_path(str(path))
    hy.llvm_state.set_diskcache_enabled(private)        # compiled code others could write is never loaded
    return hy


def built(system, tolerance, compact, opt_level=3):
    """heyoka's integrator of ``system``'s equations at (t0, y0), the state divided by :func:`scales`: a copy of
    one built once per process for each set of equations, scales, tolerance and mode."""
    factors = scales(system.layout, system.y0)
    key = (id(system.params), system.sources["rhs"], tuple(factors), tolerance, compact, opt_level)
    if key not in _BUILT:
        variables, derivatives = system.expressions(factors)
        integrator = heyoka().taylor_adaptive(list(zip(variables, derivatives)), np.zeros(len(factors)),
                                              tol=tolerance, compact_mode=compact, opt_level=opt_level)
        if len(_BUILT) >= 8:
            _BUILT.pop(next(iter(_BUILT)))
        _BUILT[key] = (system.params, integrator)          # the parameters kept: their id stays theirs
    ta = copy.copy(_BUILT[key][1])
    ta.time = float(system.t0)
    ta.state[:] = system.y0 / factors
    return ta, factors


def scales(layout, y):
    """One power of two per slice of the layout, nearest the slice's size in ``y`` (1 for a quaternion or a zero
    slice): heyoka's tolerance applies to the infinity norm of the whole state, and a spin angular momentum of
    1e23 (G-scaled) beside a position of 1e5 km would otherwise leave the position's error unchecked."""
    out = np.ones(layout.size)
    for part in layout.slices:
        size = float(np.linalg.norm(y[part.index]))
        if part.kind != "quaternion" and size > 0:
            out[part.index] = 2.0 ** round(np.log2(size))
    return out


_BUILT = {}


class StepCounter:
    """heyoka's step callback: advances the progress bar (``advance_to(t)``) every ``EVERY`` steps; a signal
    raised meanwhile (Ctrl-C) stops the propagation there."""

    EVERY = 256

    def __init__(self, advance_to):
        self.steps, self.advance_to = 0, advance_to

    def __call__(self, ta):
        self.steps += 1
        if self.steps % self.EVERY == 0:
            self.advance_to(ta.time)
        return True


class Taylor(Integrator):
    """heyoka's adaptive Taylor integrator; options ``tolerance`` (relative per step), ``compact_mode`` (None:
    compact for every System but a free body) and ``opt_level`` (LLVM's; 2 by default, which runs these systems
    as fast as 3 and builds them a third quicker; 0 builds quickest and runs several times slower).  ``nfev``
    counts the Taylor expansions of the equations, one per step; ``compile_s`` is the time the last solve took to
    get its compiled integrator."""

    name, order, kind = "taylor", None, "adaptive"
    options = {"tolerance": TOLERANCE(1e-15), "compact_mode": COMPACT_MODE, "opt_level": OPT_LEVEL(2)}

    @classmethod
    def ladder(cls, time_scale, spacing):
        """Tolerances 1e-6 ... 1e-17."""
        return [{"tolerance": 10.0**-k} for k in range(6, 18)]

    def supports(self, system):
        return bool(getattr(system, "traceable", False))

    def solve(self, system, t_out):
        t_out = self._check_times(system, t_out)
        tolerance = float(self.settings["tolerance"])
        if not 0 < tolerance < 1e-2:
            raise InputError("tolerance", tolerance, "a relative tolerance in (0, 1e-2), e.g. 1e-15")
        compact = self.settings["compact_mode"]
        if compact is None:              # unrolled code runs 2x faster, but compiles 3-100x slower beyond a free body
            compact = bool(getattr(system, "interactions", True)) or system.layout.size > 7
        started = time.perf_counter()
        ta, factors = built(system, tolerance, compact, int(self.settings["opt_level"]))
        self.compile_s = time.perf_counter() - started
        start = time.perf_counter()
        at_start = t_out[0] == ta.time                           # heyoka's grid starts at its time
        grid = t_out if at_start else np.concatenate([[ta.time], t_out])
        with progress(self.label, float(system.t0), float(t_out[-1])) as advance_to:
            outcome, _, _, steps, _, states = ta.propagate_grid(grid, callback=StepCounter(advance_to))
        states = states if at_start else states[1:]
        done = int(np.all(np.isfinite(states), axis=1).cumprod().sum())
        y_out = states[:done] * factors
        wall = time.perf_counter() - start
        solution = Trajectory(t_out[:done], normalised(system, y_out), self.name, steps, steps, wall,
                            dict(self.settings), system.layout)
        if done < t_out.size:
            err = IntegrationError(f"{self.name}: {outcome} (heyoka)", float(ta.time), ta.state * factors,
                                   "Check the scene for a close encounter, or loosen integrator.tolerance.")
            err.partial = solution
            raise err
        return solution

