"""The fast spinner's runs (scenes/stress_fast_spin) against a converged run and P96's precession rate: the
run tables (``stress.runs``, ``stress.reference``) read and labelled, each run's cost and error, and the
cheapest run at each error level."""
import math

import numpy as np

from ..analysis.figure_axis import figure_axis, fit_angles
from ..analysis.ladder import cheapest, work_precision
from ..base.errors import ScenarioError
from ..base.rotations import quat_angle
from ..integrators import METHODS, get_method
from ..scene.declaration import Outcome

# The metrics the verdict judges (the summary's comparison keys)
REFERENCE_AGREEMENT_AXIS_RAD, PRECESSION_RATE_REL_ERROR_MAX = ("reference_agreement_axis_rad",
                                                               "precession_rate_rel_error_max")


def options(run, key="stress.runs"):
    """(method, integrator options, span fraction) of one run table: the method's own option names."""
    method = run.get("method") if isinstance(run, dict) else None
    accepted = get_method(method).options if method in METHODS else {}
    if not accepted or set(run) - {"method", "span_fraction"} - set(accepted):
        raise ScenarioError(key, run, f"tables {{method = <one of {sorted(METHODS)}>, "
                                      f"<that method's options {sorted(accepted) or ''}, "
                                      "e.g. step = <days>>, span_fraction = <0-1>}")
    opts = {k: float(v) for k, v in run.items() if k in accepted}
    return method, opts, float(run.get("span_fraction", 1.0))


def label(method, opts):
    return f"{method} " + ", ".join(f"{k}={v:.3g}" for k, v in opts.items() if k != "atol")


def winner(rows, key, levels):
    """The cheapest full-span run at each error level (``key`` <= level), as text."""
    best = [(level, cheapest(rows, key, level)) for level in levels]
    return "; ".join(f"<= {level:.0e} rad: {r['run']} ({r['wall_s']:.3g} s)" for level, r in best if r) or \
        "no run below 1e-6 rad"


def precession_rate(solution, t0, delta, eps_f):
    """Mean regression rate of the figure axis (rad/d), from analysis.figure_axis.fit_angles."""
    return float(-fit_angles(solution, t0, delta, eps_f)[3][1])


def compare_run(p, run):
    system, theory, delta = run.model.spinner, run.model.theory, run.model.delta
    t, t0, span = run.times, p.span.start, p.span.end - p.span.start
    closed_form = theory.precession_rate
    ref_method, ref_opts, _ = options(p.stress.reference[0], "stress.reference")
    reference = run.integrate(system, t, "reference", ref_method, ref_opts)[0]
    ref_axis, reference_rate = figure_axis(reference), precession_rate(reference, t0, delta, theory.eps_f)
    rows = []
    for entry in p.stress.runs:
        method, opts, fraction = options(entry)
        keep, full = t <= t0 + fraction * span * (1 + 1e-12), fraction >= 1.0

        def errors(sol):
            rate = precession_rate(sol, t0, delta, theory.eps_f) if full else math.nan
            attitude_error = quat_angle(sol.quaternion, reference.quaternion[keep])
            axis_error = np.linalg.norm(figure_axis(sol) - ref_axis[keep], axis=1)
            return {"error_vs_converged_rad": float(attitude_error.max()),
                    "axis_error_vs_converged_rad": float(axis_error.max()),
                    "precession_rate_rel_error": rate / closed_form - 1,
                    "precession_rate_rel_diff_vs_converged": rate / reference_rate - 1}

        row = work_precision(system, t[keep], [(method, opts)], errors)[0]
        span_d = float(t[keep][-1] - t0)
        rows.append({"run": label(method, opts), "span_d": span_d, **row,
                     "wall_s_per_orbit": row.get("wall_s", math.nan) / span_d * 2 * math.pi / delta})
    full_rows = [r for r in rows if r["span_d"] >= span * (1 - 1e-9) and "failed" not in r]
    agreement = min(r["axis_error_vs_converged_rad"] for r in full_rows)
    rate_errors = [abs(r["precession_rate_rel_error"]) for r in full_rows]
    comparison = {
        "checks": "fast spinner (eps/delta = stress.spin_over_orbit) on a slow circle: per integrator cost "
                  "and max attitude error vs a converged run, and the fitted precession rate vs P96's "
                  "N cos n cc/aa; passes if the reference agrees with the best run to "
                  "stress.reference_agreement_max and every full-span rate is within stress.rate_rel_tol",
        "spin_over_orbit": p.stress.spin_over_orbit,
        "precession_rate_closed_form_rad_per_d": closed_form,
        "precession_rate_reference_rel_error": reference_rate / closed_form - 1,
        "reference": label(ref_method, ref_opts),
        REFERENCE_AGREEMENT_AXIS_RAD: agreement,
        "reference_agreement_attitude_rad": min(r["error_vs_converged_rad"] for r in full_rows),
        PRECESSION_RATE_REL_ERROR_MAX: max(rate_errors),
        "winner_axis_error": winner(full_rows, "axis_error_vs_converged_rad", (1e-6, 1e-8, 1e-10)),
        "winner_attitude_error": winner(full_rows, "error_vs_converged_rad", (1e-4, 1e-6, 1e-7)),
        "passed": bool(agreement < p.stress.reference_agreement_max
                       and not any("failed" in r for r in rows)
                       and max(rate_errors) < p.stress.rate_rel_tol),
    }
    return Outcome(comparison, sections={"details": {"runs": rows},
                                         "run": {"method": ",".join(r["run"] for r in rows)}})
