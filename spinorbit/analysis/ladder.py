"""Error against cost: one system run with a list of integrator settings, one row per setting.

Layer 2.  The work-precision tables of ``spinorbit bench``, the stress scenes'
per-integrator comparisons and the Moon's error-vs-runtime figure are all this
ladder with their own settings and error functions.
"""
import numpy as np

from ..base.errors import IntegrationError
from ..base.rotations import quat_angle, vector_angle
from ..integrators import get_method, simulate


def work_precision(system, t_out, settings, error, until=None):
    """Rows ``{"method", **options, "wall_s", "rhs_evaluations", "steps", **error(solution)}``, in order.

    ``settings`` is ``[(method, options), ...]`` (a registry name or Integrator class, and its
    options dict); ``error(solution)`` returns named errors ``{name: float}``.  A setting whose run
    raises IntegrationError gives ``{"method", **options, "failed": message}`` and no errors.
    ``until(row)``, if given, stops the ladder after the first row for which it is true.
    Wall times exclude compilation (see integrators.base, contract item 6).
    """
    rows = []
    for method, options in settings:
        cls = get_method(method)
        try:
            solution, _ = simulate(system, t_out, cls, options, estimate_error=False)
        except IntegrationError as failure:
            row = {"method": cls.name, **options, "failed": str(failure)}
        else:
            row = {"method": cls.name, **options, "wall_s": solution.wall_s,
                   "rhs_evaluations": solution.nfev, "steps": solution.nsteps, **error(solution)}
        rows.append(row)
        if until is not None and until(row):
            break
    return rows


def converged_error(system, t_out, step, method="rk8"):
    """An error function against a converged fixed-step run at ``step`` (checked against step/2).

    Returns (error, agreement_rad): ``agreement_rad`` is the max attitude
    difference between the runs at step and step/2, an upper bound of the
    reference's own error.
    """
    a, _ = simulate(system, t_out, method, {"step": step}, estimate_error=False)
    b, _ = simulate(system, t_out, method, {"step": step / 2}, estimate_error=False)
    agreement = float(attitude_difference(a, b).max())
    return (lambda solution: float(attitude_difference(solution, b).max())), agreement


def attitude_difference(solution, reference):
    """The angle (rad, per output) between two solutions' attitudes: the first turning body's quaternion, or the
    direction of its spin angular momentum for a gyroscopic body."""
    layout = solution.layout
    if layout.quaternions:
        return quat_angle(solution.quaternion, reference.quaternion)
    spin = next(s.name for s in layout.slices if s.name.endswith(".spin"))
    return np.asarray(vector_angle(solution.part(spin), reference.part(spin)))


def settings(methods, **options):
    """[(method, the ``options`` it accepts), ...]: one setting per method, e.g. step for the fixed-step
    methods and rtol/atol for the adaptive ones (the integrator classes' ``options`` decide)."""
    return [(method, {k: v for k, v in options.items() if k in get_method(method).options}) for method in methods]


def cheapest(rows, error, level, cost="wall_s"):
    """The row of least ``cost`` among those whose ``error`` is at most ``level`` (failed rows skipped); None
    if none."""
    within = [r for r in rows if "failed" not in r and r[error] <= level]
    return min(within, key=lambda r: r[cost]) if within else None
