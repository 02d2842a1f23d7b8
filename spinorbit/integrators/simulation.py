"""System + output times + integrator -> Trajectory, with its own error estimate: the one integrator door.

Every integration goes through :func:`simulate` (the scenes, the starts of the models, the ladders and the
Lyapunov flows of the analyses): it splits a span on both sides of t0 into runs away from it, hooks the
progress bar and the checkpoint, and estimates the error.

Every run reports a point on the error-against-run-time plane: the wall time of the solve and an estimate of
its integration error, from a second run of the same method:

* fixed-step methods of order p: a run at twice the step, and Richardson's estimate |y_2h - y_h| / (2^p - 1)
  of the error of y_h (half the cost of the run itself; it assumes the step is in the method's asymptotic
  regime, which the benchmarks' work-precision ladders show for every shipped scene);
* adaptive methods (and fixed-step runs unstable at twice the step): a run with tolerances divided by 100 (or
  half the step), and |y - y_ref|.

The estimate is read off the System's layout: the attitudes (every quaternion, and a gyroscopic spin's
direction) as an angle in arcsec, the angular velocities relative to their size, the positions in km.
"""
from concurrent.futures import ThreadPoolExecutor

import numpy as np

from ..base.constants import ARCSEC
from ..base.errors import InputError, IntegrationError
from ..base.rotations import quat_angle, vector_angle
from .base import Trajectory, normalised
from .registry import get_method


def error_estimate(method_cls, options, system, t_out):
    """(other solution, the outputs it covers, scale, how): the estimate's second run and how to read it.

    Fixed-step methods of known order: a run at twice the step to every other output (with
    outputs one step apart, it lands on them with no interpolation), the difference over
    2^p - 1.  Otherwise (when twice the step is unstable, or every other output is t0 itself) a refined run, the
    difference as it is.
    """
    settings = {**method_cls.defaults(), **options}
    if "step" in settings and method_cls.order and np.any(t_out[::2] != system.t0):
        try:
            coarse = method_cls(**{**settings, "step": 2 * settings["step"]})
            coarse.label = None
            every_other = slice(None, None, 2)
            return (coarse.solve(system, t_out[every_other]), every_other, 2.0**method_cls.order - 1.0,
                    f"Richardson, run at twice the step, order {method_cls.order}")
        except IntegrationError:             # twice the step is unstable: refine instead
            pass
    refined = method_cls(**method_cls.refined(options))
    refined.label = None
    return (refined.solve(system, t_out), slice(None), 1.0,
            "difference from a run at half the step or tolerances / 100")


def differences(layout, states, other, scale):
    """{integration_error_*: value} of two runs' states by kind of slice: the attitudes (arcsec; quaternions and
    gyroscopic spins' directions), the angular velocities in body axes (``*.omega``, relative to their size), the
    positions (``*.r``, km), and every other slice relative to its size (``integration_error_<slice>_rel``)."""
    attitude, omega, position, out = [0.0], [], [], {}
    for part in layout.slices:
        a, b = states[:, part.index], other[:, part.index]
        relative = np.abs(a - b).max() / max(np.abs(b).max(), 1e-300) / scale
        if part.kind == "quaternion":
            attitude.append(quat_angle(a, b).max())
        elif part.name.endswith(".spin"):
            attitude.append(vector_angle(a, b).max())
        elif part.name.endswith(".r"):
            position.append(np.linalg.norm(a - b, axis=1).max())
        elif part.name.endswith(".omega"):
            omega.append(relative)
        else:
            out[f"integration_error_{part.name.replace('.', '_')}_rel"] = float(relative)
    out["integration_error_attitude_arcsec"] = float(max(attitude) / scale / ARCSEC)
    if omega:
        out["integration_error_omega_rel"] = float(max(omega))
    if position:
        out["integration_error_position_km"] = float(max(position) / scale)
    return out


def simulate(system, t_out, method="dop853", options=None, estimate_error=True, checkpoint=None, label=None):
    """Integrate; return (solution, {method, wall_s, rhs_evaluations, steps, integration_error_*, ...}), the
    solution's rows in the order of ``t_out``.

    Outputs may come in any order, repeat, lie on both sides of ``system.t0`` or run toward it: each side's
    distinct times are integrated away from t0 in a run of their own (spinorbit.integrators' contract) and the
    rows put back in order; an output at t0 is the start state (with no other output, nothing is integrated and
    the error is zero).  Only a run asked as the method takes it (one side, distinct times, away from t0) is
    checkpointed; a failing run's IntegrationError holds that run's partial solution.

    ``checkpoint`` (spinorbit.edge.checkpoint.Checkpoint or None) is offered the outputs as the run goes, by a method
    that can resume (rk8 landing on its outputs; the others run without one); ``label`` names the progress bar
    (default: the method).  A compiled method's
    error-estimate run goes on in a second thread meanwhile (the kernels release the GIL), so on two cores it
    adds little to the wall time; ``wall_s`` is the main run's own.
    """
    t_out = np.asarray(t_out, dtype=float)
    if t_out.ndim != 1 or not t_out.size or not np.all(np.isfinite(t_out)):
        raise InputError("t_out", f"{t_out.size} output times in {t_out.ndim} dimensions"
                         + ("" if np.all(np.isfinite(t_out)) else ", not all finite"),
                         "a non-empty 1-d array of finite times")
    runs = away_from(system.t0, t_out)
    if len(runs) == 1 and np.array_equal(runs[0], t_out):
        return _run(system, t_out, method, options, estimate_error, checkpoint, label)
    done = [_run(system, times, method, options, estimate_error, None, _side(label, system.t0, times))
            for times in runs]
    return _gathered(system, t_out, runs, done, method, options, estimate_error)


def _side(label, t0, times):
    """The progress label of one side's run: ``label`` and which way it goes from t0."""
    return None if label is None else f"{label} ({'backward' if times[0] < t0 else 'forward'})"


def _run(system, t_out, method, options, estimate_error, checkpoint, label):
    """(solution, point) of one run away from t0 over distinct times (the method's contract)."""
    method_cls = get_method(method)
    options = options or {}
    integrator = method_cls(**options)
    integrator.checkpoint = checkpoint if method_cls.resumable else None
    integrator.label = label or method_cls.name
    concurrent = estimate_error and method_cls.kind != "adaptive"
    with ThreadPoolExecutor(max_workers=1) as pool:
        estimate = pool.submit(error_estimate, method_cls, options, system, t_out) if concurrent else None
        solution = integrator.solve(system, t_out)
    point = {"method": method_cls.name, "wall_s": solution.wall_s, "rhs_evaluations": solution.nfev,
             "steps": solution.nsteps}
    if "step" in integrator.settings:
        point["step_d"] = float(integrator.settings["step"])
    if hasattr(integrator, "compile_s"):          # the Taylor integrator's trace and build (heyoka)
        point["compile_s"] = integrator.compile_s
    if estimate_error:
        other, covered, scale, how = (estimate.result() if concurrent
                                      else error_estimate(method_cls, options, system, t_out))
        point.update(differences(system.layout, solution.y[covered], other.y, scale),
                     integration_error_method=how)
    return solution, point


def away_from(t0, t_out):
    """The runs that give every output: the distinct times after t0 ascending, then those before it descending,
    an output at t0 heading the first of them (it aligns a fixed step's Richardson run); none when every output
    is at t0."""
    times = np.unique(t_out)
    runs = [side for side in (times[times > t0], times[times < t0][::-1]) if side.size]
    if runs and np.any(times == t0):
        runs[0] = np.concatenate([[t0], runs[0]])
    return runs


def _gathered(system, t_out, runs, done, method, options, estimate_error):
    """One (solution, point) from the runs of each side (the start state at t0), rows in the order of t_out:
    costs summed, each integration error the largest of the runs' (zero with no run)."""
    method_cls = get_method(method)
    start = normalised(system, system.y0[None, :])
    times = np.concatenate([[system.t0], *runs])
    states = np.concatenate([start, *(solution.y for solution, _ in done)])
    distinct, first = np.unique(times, return_index=True)
    y = states[first[np.searchsorted(distinct, t_out)]]
    solutions = [solution for solution, _ in done]
    steps = [solution.nsteps for solution in solutions]
    merged = Trajectory(t_out.copy(), y, method_cls.name, sum(s.nfev for s in solutions),
                      None if None in steps else sum(steps), sum(s.wall_s for s in solutions),
                      dict(solutions[0].options if solutions else {**method_cls.defaults(), **(options or {})}),
                      system.layout)
    point = {**(done[0][1] if done else {"method": method_cls.name}),
             "wall_s": merged.wall_s, "rhs_evaluations": merged.nfev, "steps": merged.nsteps}
    if estimate_error:
        for key, value in differences(system.layout, start, start, 1.0).items():
            point[key] = max([value, *(p[key] for _, p in done if key in p)])
        if not done:
            point["integration_error_method"] = "none: every output is the start state"
    return merged, point
