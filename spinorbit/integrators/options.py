"""The integrators' options, each declared once: its meaning, unit, plausible range, what a step over the span
counts, and how a markedly more accurate run sets it.

A method's class picks the options it accepts (``Integrator.options``: name -> :class:`Option`, with the
method's own default); the scenario schema's ``integrator.*`` keys, the error estimate's refined run
(``Integrator.refined``) and the option lists shown to users all read these declarations.
"""
import dataclasses
import math
from dataclasses import dataclass
from typing import Callable

EPS = 2.220446049250313e-16
SCIPY_RTOL_FLOOR = 2.3e-14          # scipy raises a smaller rtol to 100 eps (with a warning)
HEYOKA_TOLERANCE_FLOOR = 1e-18      # heyoka's: below eps it raises the order, the floor is rounding


@dataclass(frozen=True)
class Option:
    """One integrator option: ``default`` (the method's), ``help``, ``unit`` ("d" for a duration given as a
    quantity, "" for a number), its plausible range (``min``, ``max``, ``positive``), ``count`` (what a step
    over the span counts, for the run's cost, or None) and ``refine`` (value -> the value of a markedly more
    accurate run; None: kept)."""

    default: object
    help: str
    unit: str = ""
    min: float = -math.inf
    max: float = math.inf
    positive: bool = False
    count: str | None = None
    refine: Callable | None = None
    numeric: bool = True            # checked as a number at the edge (not a choice of text)

    def __call__(self, default):
        """The same option with a method's own default."""
        return dataclasses.replace(self, default=default)


def _halved(step):
    return step / 2


def _rtol(value):
    return max(value / 100, SCIPY_RTOL_FLOOR)


def _atol(value):
    return value / 100


def _tolerance(value):
    return max(value / 100, HEYOKA_TOLERANCE_FLOOR)


# scipy silently raises rtol below 100 eps, and looser than 1e-3 (scipy's own default) an attitude run is nonsense
# (rtol 0.1 on p93_bounded: zeta off by 62 deg); atol below 1e-20 is under the rounding of any state.
STEP = Option(1.0, "fixed step", unit="d", positive=True, count="integrator steps", refine=_halved)
MAX_STEPS = Option(10**9, "most steps before the run stops", positive=True)
RTOL = Option(1e-12, "relative tolerance", min=100 * EPS, max=1e-3, refine=_rtol)
ATOL = Option(1e-14, "absolute tolerance", min=1e-20, max=1e-3, refine=_atol)
MAX_STEP = Option(math.inf, "largest step, days", positive=True, count="adaptive steps (at max_step)")
TOLERANCE = Option(1e-15, "Taylor (heyoka) tolerance, relative per step", min=1e-18, max=1e-6, refine=_tolerance)
FREE_FLOW = Option("symmetric", "the free rotation between kicks: 'symmetric' or 'euler'", numeric=False)
COMPACT_MODE = Option(None, "heyoka's compact mode (None: compact for every System but a free body)",
                      numeric=False)
OPT_LEVEL = Option(2, "LLVM's optimisation level (0-3)", min=0, max=3)

# Every option some method accepts, by name (the defaults here are the declarations', a method sets its own).
OPTIONS = {"step": STEP, "max_steps": MAX_STEPS, "rtol": RTOL, "atol": ATOL, "max_step": MAX_STEP,
           "tolerance": TOLERANCE, "free_flow": FREE_FLOW, "compact_mode": COMPACT_MODE, "opt_level": OPT_LEVEL}
