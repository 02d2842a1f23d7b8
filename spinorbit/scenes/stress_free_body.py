"""Stress cases of the torque-free rigid body (Euler ch. 15 §808), each passing or failing on a number.

``stress.case``: ``flip`` (intermediate-axis flips of I = 0.3, 0.35, 0.4, omega0 = 0.1, 15, 0.1 rad/d:
the period over ``stress.flips`` flips of w_y vs theory.FreeRigidBody, 12.335 d); ``degenerate``
(A = B = C under a point-mass torque: exactly zero torque, uniform rotation; A = B (1 + 1e-12)
torque-free vs theory.axisymmetric_attitude); ``shapes`` (prolate and oblate, (C - A)/C = 1e-8 ... 0.9,
vs theory.axisymmetric_attitude); ``long_run`` (``stress.steps`` steps of the HLW body: drift of |L|
and of the energy, first and last tenth, bounded for the splittings).  Every case runs its methods
through analysis.ladder.work_precision.
"""
import numpy as np

from ..analysis.theory import FreeRigidBody
from ..comparisons.free_body_stress import PASSED, Q0, attitude_error, degenerate, flip, long_run, shapes
from ..models.assemblies.idealised import free_body
from ..scene.declaration import Model, Outcome, Scene
from ..scene.params import Params, key, table
from ..scene.verdict import Check, Verdict
from ..starts.idealised import check_methods
from . import common

CASES = ("flip", "degenerate", "shapes", "long_run")
VERDICT = Verdict("the case's closed form or invariant", (Check(
    "its criteria", PASSED,
    source="the case's criteria (module docstring; benchmarks/RESULTS.md, stress scenes)"),))


@table
class StressTable:
    case: str = key(type=str, choices=CASES)
    flips: int = key(type=int, default=1000, help="flip: number of flips measured")
    flattenings: list = key(type=list, default=[1e-8, 1e-6, 1e-4, 1e-2, 0.3, 0.9],
                            help="shapes: (C - A)/C")
    methods: list = key(type=list, default=["rk8", "strang", "suzuki4", "dop853"],
                        help="methods compared")
    steps: int = key(type=int, default=10**7, help="long_run: steps per method")


@table
class BodyTable:
    moments: np.ndarray = key(unit="", size=3, default=np.array([0.3, 0.35, 0.4]),
                              help="A <= B <= C (flip, long_run)")
    omega0: np.ndarray = key(unit="rad/d", size=3, default=np.array([0.1, 15.0, 0.1]), help="initial body omega")


@table
class StressFreeBodyParams(Params):
    stress: StressTable
    body: BodyTable


CHECKS = {
    "flip": "intermediate-axis flip period over many flips vs closed form; passes within 1e-3 relative",
    "degenerate": "A = B = C: torque exactly 0, uniform rotation; A = B(1 + 1e-12) vs closed form; "
                  "passes below 1e-9 rad",
    "shapes": "prolate/oblate, (C - A)/C = 1e-8 ... 0.9 vs axisymmetric closed form; passes below 1e-9 rad",
    "long_run": "|L| and energy drift over many steps; passes if the splittings keep |L| to 1e-11 and their "
                "energy error in the last tenth below twice that of the first (no secular growth)"}


def build(p, times):
    """No main run: the case runs its methods (cases.py); for bench, the case's torque-free body."""
    check_methods(p.stress.methods)
    return Model(None, bench_system=free_body(p.body.moments, Q0, p.body.omega0))


def bench(p, model, times):
    """Attitude error against the closed form (theory.FreeRigidBody), rad."""
    error = attitude_error(FreeRigidBody(p.body.moments, p.body.omega0, Q0).attitude(times - p.span.start))
    return lambda solution: error(solution)["attitude_error_max_rad"]


def compare_run(p, run):
    cases = {"flip": flip, "degenerate": degenerate, "shapes": shapes, "long_run": long_run}
    comparison, details = cases[p.stress.case](p)
    return Outcome({"checks": CHECKS[p.stress.case], **comparison},
                   sections={"details": details, "run": {"method": ",".join(p.stress.methods)}})


SCENE = Scene(StressFreeBodyParams, build, compare_run, VERDICT, time_scales=common.rigid_body_time_scales,
              bench=bench)
