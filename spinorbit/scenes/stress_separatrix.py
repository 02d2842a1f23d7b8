"""Stress: planar libration a hair off Euler's separatrix (ch. 16 P93, §826, C = n (1 +- 1e-9)).

Starting with the axis A on the line to F (zeta = 0) and zeta'^2 = C + n, the
body either just fails to reach zeta = 90 deg (C < n: bounded, it stops at
arcsin k, k^2 = (1 + C/n)/2, after K(k^2)/sqrt(2n)) or just passes it (C > n:
circulation, 90 deg after K(m)/sqrt(C + n), m = 2n/(C + n)); both times are
~ ln(1/|C/n - 1|) long and their derivative with respect to C is 1/(C - n):
an integrator must hold Euler's energy constant to far better than 1e-9 n.
The measured time (zeta' = 0, or zeta = 90 deg) is compared with the closed
form of theory.PlanarLibration.  Passes when every method gets the side of
the separatrix right and the time within ``stress.time_rel_tol``.
"""
import numpy as np

from ..comparisons import separatrix_p93 as vs
from ..scene.declaration import Model, Outcome, Scene
from ..scene.params import Params, key, table
from ..scene.verdict import Check, Verdict
from ..starts import separatrix_p93 as start
from . import common


def verdict(p, comparison):
    """Side of the separatrix and time to 90 deg against §826, every method and offset."""
    return Verdict("§826 closed form", (
        Check("time to 90°", vs.TIME_REL_ERROR_MAX, p.stress.time_rel_tol, "",
              "stress.time_rel_tol: the closed-form time is exact; the margin covers the integrators' "
              "error, amplified near the separatrix (up to 4e-6 measured, benchmarks/RESULTS.md)"),
        Check("side and time", vs.PASSED, source="each run on the closed form's side of the separatrix")))


@table
class BodyTable:
    moments: np.ndarray = key(unit="", size=3, help="principal moments A < B <= C")


@table
class StressTable:
    offsets: list = key(type=list, default=[-1e-9, 1e-9], help="C/n - 1 for each run")
    methods: list = key(type=list, default=["rk8", "suzuki4", "dop853"])
    time_rel_tol: float = key(unit="", default=1e-4, help="pass threshold on the time to 90 deg")


@table
class StressSeparatrixParams(Params):
    body: BodyTable
    orbit: common.CircularCentreTable
    stress: StressTable


def build(p, times):
    """No main run: a run per offset and method (compare); for bench, the run just below the separatrix."""
    runs = start.runs(p)
    return Model(None, runs=runs, bench_system=runs[0][1])


def bench(p, model, times):
    """Attitude error against the closed form below the separatrix, rad."""
    return vs.attitude_error(p, model.runs[0][2], times)


def compare_run(p, run):
    comparison, rows = vs.compare(p, run.model.runs, run.times)
    return Outcome(comparison, sections={"details": rows, "run": {"method": ",".join(p.stress.methods)}})


SCENE = Scene(StressSeparatrixParams, build, compare_run, verdict, time_scales=common.rigid_body_time_scales,
              bench=bench)
