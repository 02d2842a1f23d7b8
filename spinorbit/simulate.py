"""Layer 3: system + output times + integrator -> Solution, with its own error estimate.

Every run reports a point on the error-against-run-time plane: the wall time
of the solve and an estimate of its integration error, measured against a
second run at refined settings (half the step for fixed-step methods, tolerances
divided by 100 for adaptive ones).  The estimate is the maximum attitude
difference between the two runs, in arcsec.
"""
import numpy as np

from .constants import ARCSEC
from .integrators import get_method
from .rotations import quat_angle


def refined_options(method_cls, options):
    """Options for a run markedly more accurate than ``options`` with the same method."""
    refined = {**method_cls.options, **options}
    if "step" in refined:
        refined["step"] = refined["step"] / 2
    for tol in ("rtol", "atol"):
        if tol in refined:
            refined[tol] = max(refined[tol] / 100, 2.3e-14 if tol == "rtol" else 0.0)   # scipy floor: 100 eps
    return refined


def simulate(system, t_out, method="dop853", options=None, estimate_error=True):
    """Integrate; return (solution, {wall_s, integration_error_attitude_arcsec, ...})."""
    method_cls = get_method(method)
    options = options or {}
    solution = method_cls(**options).solve(system, t_out)
    point = {"method": method_cls.name, "wall_s": solution.wall_s,
             "rhs_evaluations": solution.nfev, "steps": solution.nsteps}
    if estimate_error:
        reference = method_cls(**refined_options(method_cls, options)).solve(system, t_out)
        point["integration_error_attitude_arcsec"] = float(
            quat_angle(solution.quaternion, reference.quaternion).max() / ARCSEC)
        scale = np.abs(reference.omega).max()
        point["integration_error_omega_rel"] = float(np.abs(solution.omega - reference.omega).max() / scale)
    return solution, point
