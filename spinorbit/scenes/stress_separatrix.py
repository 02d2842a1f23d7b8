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
import math

import numpy as np

from ..analysis.ladder import settings, work_precision
from ..analysis.planar_libration import crossing_times, planar_system, zeta_from_solution
from ..base.errors import ScenarioError
from ..integrators import METHODS
from ..scene.declaration import Model, Outcome, Scene
from ..scene.params import Params, key, table
from ..scene.verdict import Check, Verdict
from . import common


def verdict(p, comparison):
    """Side of the separatrix and time to 90 deg against §826, every method and offset."""
    return Verdict("§826 closed form", (
        Check("time to 90°", "time_rel_error_max", p.stress.time_rel_tol, "",
              "stress.time_rel_tol: the closed-form time is exact; the margin covers the integrators' "
              "error, amplified near the separatrix (up to 4e-6 measured, benchmarks/RESULTS.md)"),
        Check("side and time", "passed", source="each run on the closed form's side of the separatrix")))


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


def _setup(p, offset):
    from ..analysis.theory import PlanarLibration, libration_n
    from ..orbits.analytic import CircularOrbits

    gm, s, delta = p.orbit.gm, p.orbit.radius, p.orbit.rate
    n = libration_n(p.body.moments, gm, s)
    zeta_dot0 = math.sqrt(n * (2.0 + offset))
    orbit = CircularOrbits(("F",), [gm], [s], [delta], phase=[-delta * p.span.start])
    theory = PlanarLibration(n, 0.0, zeta_dot0)
    return planar_system(p.body.moments, orbit, p.span.start, 0.0, zeta_dot0, delta), theory


def time_to_90(theory):
    """Closed-form time from zeta = 0 to the top: K/sqrt(2n) (bounded) or K(m)/sqrt(C + n)
    (circulation), §826."""
    return theory.period / 4 if theory.case == "bounded" else theory.period / 2


def measure(solution, t0, delta):
    """(case, time): 'bounded' and the first zeta' = 0, or 'circulation' and the first zeta = 90 deg."""
    dt = solution.t - t0
    zeta = zeta_from_solution(solution, delta * dt)
    up = crossing_times(dt, zeta, math.pi / 2)
    zeta_dot = delta - solution.omega[:, 2]
    stop = crossing_times(dt, -zeta_dot, 0.0)
    if up.size and (not stop.size or up[0] < stop[0]):
        return "circulation", float(up[0])
    return ("bounded", float(stop[0])) if stop.size else ("none", math.nan)


def build(p, times):
    """No main run: a run per offset and method (compare); for bench, the run just below the separatrix."""
    for method in p.stress.methods:
        if not isinstance(method, str) or method not in METHODS:
            raise ScenarioError("stress.methods", method, f"method names, of {sorted(METHODS)}")
    runs = [(float(offset), *_setup(p, float(offset))) for offset in p.stress.offsets]
    return Model(None, runs=runs, bench_system=runs[0][1])


def bench(p, model, times):
    """Attitude error against the closed form below the separatrix, rad."""
    theory, delta = model.runs[0][2], p.orbit.rate
    zeta_exact = theory.zeta(times - p.span.start)
    return lambda solution: float(np.abs(zeta_from_solution(solution, delta * (solution.t - p.span.start))
                                         - zeta_exact).max())


def compare_run(p, run):
    rows, passed, delta = {}, True, p.orbit.rate
    for offset, system, theory in run.model.runs:
        expected = time_to_90(theory)

        def measured(solution):
            case, took = measure(solution, p.span.start, delta)
            return {"case_closed_form": theory.case, "case_measured": case,
                    "time_to_90deg_closed_form_d": expected,
                    "time_to_90deg_measured_d": took, "time_rel_error": took / expected - 1}

        methods = settings(p.stress.methods, step=0.01, rtol=1e-13, atol=1e-15)
        for row in work_precision(system, run.times, methods, measured):
            passed &= (row.get("case_measured") == theory.case
                       and abs(row["time_rel_error"]) < p.stress.time_rel_tol)
            rows[f"{offset:+g}/{row['method']}"] = row
    comparison = {"checks": "side of the P93 separatrix and time to approach 90 deg vs §826 closed form, "
                            f"C = n(1 +- 1e-9); passes within {p.stress.time_rel_tol:g} relative",
                  "time_rel_error_max": max(abs(r.get("time_rel_error", math.inf)) for r in rows.values()),
                  "passed": bool(passed)}
    return Outcome(comparison, sections={"details": rows, "run": {"method": ",".join(p.stress.methods)}})


SCENE = Scene(StressSeparatrixParams, build, compare_run, verdict, time_scales=common.rigid_body_time_scales,
              bench=bench)
