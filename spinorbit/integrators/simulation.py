"""System + output times + integrator -> Solution, with its own error estimate: the one integrator door.

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

from ..constants import ARCSEC
from ..errors import IntegrationError
from ..rotations import quat_angle, vector_angle
from .registry import get_method


def error_estimate(method_cls, options, system, t_out):
    """(other solution, the outputs it covers, scale, how): the estimate's second run and how to read it.

    Fixed-step methods of known order: a run at twice the step to every other output (with
    outputs one step apart, it lands on them with no interpolation), the difference over
    2^p - 1.  Otherwise (or when twice the step is unstable) a refined run, the difference as it is.
    """
    settings = {**method_cls.defaults(), **options}
    if "step" in settings and method_cls.order:
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

    Outputs may lie on both sides of ``system.t0``, or run toward it (a span that a start outside it reaches):
    each side is integrated away from t0 in its own run (spinorbit.integrators' contract) and the rows put back
    in order; only a run in one direction is checkpointed.

    ``checkpoint`` (spinorbit.checkpoint.Checkpoint or None) is offered the outputs as the run goes, by a method
    that can resume (rk8 landing on its outputs; the others run without one); ``label`` names the progress bar
    (default: the method).  A compiled method's
    error-estimate run goes on in a second thread meanwhile (the kernels release the GIL), so on two cores it
    adds little to the wall time; ``wall_s`` is the main run's own.
    """
    t_out = np.asarray(t_out, dtype=float)
    sides = away_from(system.t0, t_out)
    if len(sides) > 1 or not np.array_equal(sides[0], np.arange(t_out.size)):
        runs = [simulate(system, t_out[rows], method, options, estimate_error, None, label) for rows in sides]
        return _merged(t_out, sides, runs)
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
    """Index arrays of ``t_out`` in the order of runs away from t0: the outputs after t0 ascending, then those
    before it descending (one array when every output lies on one side in that order); outputs at t0 start the
    run after it, or the run before it when there is none after."""
    order = np.argsort(t_out, kind="stable")
    descending = np.argsort(-t_out, kind="stable")       # equal times keep their order on both sides
    at = order[t_out[order] == t0]
    after, before = order[t_out[order] > t0], descending[t_out[descending] < t0]
    if after.size or not before.size:
        after = np.concatenate([at, after])
    else:
        before = np.concatenate([at, before])
    return [rows for rows in (after, before) if rows.size] or [np.arange(t_out.size)]


def _merged(t_out, sides, runs):
    """One (solution, point) from the runs of each side, rows back in the order of t_out."""
    from dataclasses import replace

    y = np.empty((t_out.size, runs[0][0].y.shape[1]))
    for rows, (solution, _) in zip(sides, runs):
        y[rows] = solution.y
    first, point = runs[0]
    merged = replace(first, t=t_out.copy(), y=y, nfev=sum(s.nfev for s, _ in runs),
                     nsteps=None if any(s.nsteps is None for s, _ in runs) else sum(s.nsteps for s, _ in runs),
                     wall_s=sum(s.wall_s for s, _ in runs))
    point = {**point, "wall_s": merged.wall_s, "rhs_evaluations": merged.nfev, "steps": merged.nsteps}
    for key in point:
        if key.startswith("integration_error_") and isinstance(point[key], float):
            point[key] = max(p.get(key, 0.0) for _, p in runs)
    return merged, point
