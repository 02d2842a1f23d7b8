"""stress_separatrix's comparison: each run a hair off Euler's separatrix (P93, §826), by every method, on
the closed form's side and reaching the top (zeta' = 0, or zeta = 90 deg) at the closed form's time."""
import math

import numpy as np

from ..analysis.planar_libration import crossing_times, zeta_from_solution

# The metrics the verdict judges (the summary's comparison keys)
TIME_REL_ERROR_MAX, PASSED = "time_rel_error_max", "passed"


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


def attitude_error(p, theory, times):
    """bench's error: the largest |zeta - the closed form's| of a solution, rad."""
    zeta_exact = theory.zeta(times - p.span.start)
    return lambda solution: float(np.abs(zeta_from_solution(solution, p.orbit.rate * (solution.t - p.span.start))
                                         - zeta_exact).max())


def compare(p, runs, times):
    """(metrics, {"<offset>/<method>": row}) of every run of ``runs`` ([(offset, System, closed form)]) by
    each of ``stress.methods`` (analysis.ladder.work_precision)."""
    from ..analysis.ladder import settings, work_precision

    rows, passed, delta = {}, True, p.orbit.rate
    for offset, system, theory in runs:
        expected = time_to_90(theory)

        def measured(solution):
            case, took = measure(solution, p.span.start, delta)
            return {"case_closed_form": theory.case, "case_measured": case,
                    "time_to_90deg_closed_form_d": expected,
                    "time_to_90deg_measured_d": took, "time_rel_error": took / expected - 1}

        methods = settings(p.stress.methods, step=0.01, rtol=1e-13, atol=1e-15)
        for row in work_precision(system, times, methods, measured):
            passed &= (row.get("case_measured") == theory.case
                       and abs(row["time_rel_error"]) < p.stress.time_rel_tol)
            rows[f"{offset:+g}/{row['method']}"] = row
    comparison = {"checks": "side of the P93 separatrix and time to approach 90 deg vs §826 closed form, "
                            f"C = n(1 +- 1e-9); passes within {p.stress.time_rel_tol:g} relative",
                  TIME_REL_ERROR_MAX: max(abs(r.get("time_rel_error", math.inf)) for r in rows.values()),
                  PASSED: bool(passed)}
    return comparison, rows
