"""Stress: a fast, nearly symmetric spinner on a slow orbit (spin/orbit frequency ratio 1e5).

An oblate body (A ~ B < C) spins at eps about its figure axis, at obliquity n
to the plane of a point mass F on a uniform circle at delta = eps/ratio
(Euler ch. 16 P96, §844-849).  Its figure axis regresses about the orbit pole
at the averaged rate N cos n cc/aa (theory.SymmetricPrecession with the
gyroscopic ratio aa/cc; N = theory.precession_constant, cc = (A + B)/2,
the B - A part averages out over the spin).  GM/s^3 is set by
``stress.precession_over_orbit`` = N/delta (the orbit is prescribed, not Keplerian).

Every run in ``stress.runs`` (a method, its options, a span fraction; analysis.ladder.work_precision)
reports its cost (scaled per orbit when it covers only ``span_fraction`` of the span) and its errors
against a converged run (``stress.reference``): the attitude (which includes the spin phase, 6e5 rad
per orbit, so rounding alone leaves ~1e-8 rad), the figure axis (P96's precession and nutation), and
the precession rate fitted over the span (§847) against the closed form, first order in N/delta.
Passes when the reference's figure axis agrees with the best other run to
``stress.reference_agreement_max`` rad and every full-span rate is within ``stress.rate_rel_tol``.
"""
import math

import numpy as np

from ...analysis.figure_axis import figure_axis, fit_angles
from ...analysis.ladder import work_precision
from ...models.assemblies.idealised import under_point_masses
from ...rotations import quat_angle
from ...scene import Model, Outcome, Scene
from ...schema import ANGLE, SPIN, Key
from ...verdict import Check, Verdict
from .. import common
from .runs import label, options, winner


def verdict(p, comparison):
    """Converged runs agree, and every full-span run's precession rate matches P96's N cos n."""
    return Verdict("a converged suzuki4 run; P96's N cos n", (
        Check("converged runs agree", "reference_agreement_axis_rad", p.stress.reference_agreement_max,
              " rad", "stress.reference_agreement_max: the figure axis of two converged runs"),
        Check("rate vs P96", "precession_rate_rel_error_max", p.stress.rate_rel_tol, "",
              "P96 is first order in N/delta = 1e-3 (stress.rate_rel_tol)")))


SCHEMA = {
    "body.moments": Key(unit="", size=3, help="A <= B < C, nearly symmetric about C"),
    "body.spin": Key(**SPIN, help="spin rate eps about the figure axis"),
    "body.obliquity": Key(**ANGLE, help="angle n of the figure axis from the orbit pole"),
    "stress.spin_over_orbit": Key(unit="", default=1e5, help="eps/delta"),
    "stress.precession_over_orbit": Key(unit="", default=1e-3, help="N/delta (sets GM/s^3)"),
    "stress.runs": Key(type=list,
                       help="[{method, <its options, e.g. step (d) or rtol, atol>, span_fraction}]"),
    "stress.reference": Key(type=list, help="[{method, <its options>}]: the converged run"),
    "stress.rate_rel_tol": Key(unit="", default=1e-3, help="pass: |rate/closed form - 1| for full-span runs"),
    "stress.reference_agreement_max": Key(
        unit="", default=1e-9, help="pass: figure-axis difference, reference vs best other run, rad"),
}
RADIUS = 1.0          # F's distance (length unit arbitrary: only GM/s^3 enters)


def build(p, times):
    """No main run (a converged reference and the ladder of ``stress.runs``, compare): the spinner started on
    Euler's forced solution (§844), its closed form."""
    from ...orbits.analytic import CircularOrbits
    from ...theory import SymmetricPrecession, p96_initial_state, precession_constant

    body = common.rigid_body(p)
    a_, b_, aa = body.moments
    cc = 0.5 * (a_ + b_)
    eps, n = p["body.spin"], p["body.obliquity"]
    delta = eps / p["stress.spin_over_orbit"]
    big_n = p["stress.precession_over_orbit"] * delta
    gm = big_n / precession_constant(1.0, RADIUS, eps, aa, cc)          # N is proportional to GM
    theory = SymmetricPrecession(eps, delta, big_n, n, ratio=aa / cc)
    e, f, _ = theory.coefficients()
    q0, omega0 = p96_initial_state(n, eps, e + f, 0.0)
    t0 = p.t_start
    orbit = CircularOrbits(("F",), [gm], [RADIUS], [delta], phase=[-delta * t0])
    system = under_point_masses(body.moments, orbit, q0, omega0, t0, "fast spinner, slow orbit")
    return Model(None, spinner=system, theory=theory, delta=delta)


def precession_rate(solution, t0, delta, eps_f):
    """Mean regression rate of the figure axis (rad/d), from p96_precession.fit_angles."""
    return float(-fit_angles(solution, t0, delta, eps_f)[3][1])


def compare_run(p, run):
    system, theory, delta = run.model.spinner, run.model.theory, run.model.delta
    t, t0, span = run.times, p.t_start, p.t_end - p.t_start
    closed_form = theory.precession_rate
    ref_method, ref_opts, _ = options(p["stress.reference"][0], "stress.reference")
    reference = run.integrate(system, t, "reference", ref_method, ref_opts)[0]
    ref_axis, reference_rate = figure_axis(reference), precession_rate(reference, t0, delta, theory.eps_f)
    rows = []
    for entry in p["stress.runs"]:
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
        "spin_over_orbit": p["stress.spin_over_orbit"],
        "precession_rate_closed_form_rad_per_d": closed_form,
        "precession_rate_reference_rel_error": reference_rate / closed_form - 1,
        "reference": label(ref_method, ref_opts),
        "reference_agreement_axis_rad": agreement,
        "reference_agreement_attitude_rad": min(r["error_vs_converged_rad"] for r in full_rows),
        "precession_rate_rel_error_max": max(rate_errors),
        "winner_axis_error": winner(full_rows, "axis_error_vs_converged_rad", (1e-6, 1e-8, 1e-10)),
        "winner_attitude_error": winner(full_rows, "error_vs_converged_rad", (1e-4, 1e-6, 1e-7)),
        "passed": bool(agreement < p["stress.reference_agreement_max"]
                       and not any("failed" in r for r in rows)
                       and max(rate_errors) < p["stress.rate_rel_tol"]),
    }
    return Outcome(comparison, sections={"details": {"runs": rows},
                                         "run": {"method": ",".join(r["run"] for r in rows)}})


SCENE = Scene(SCHEMA, build, compare_run, verdict, time_scales=common.rigid_body_time_scales(SCHEMA))
