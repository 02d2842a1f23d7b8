"""free_body's comparison: the integrated angular velocity and attitude against Euler's closed form
(spinorbit.analysis.theory.FreeRigidBody, ch. 15 §808)."""
import numpy as np

from ..base.constants import ARCSEC
from ..base.rotations import quat_angle

# The metrics the verdict judges (the summary's comparison keys)
ATTITUDE_MAX_ERROR_RAD = "attitude_max_error_vs_closed_form_rad"
OMEGA_MAX_REL_ERROR = "omega_max_rel_error_vs_closed_form"


def compare(p, solution, exact):
    """(metrics, days from span.start, the attitude's error against ``exact`` at each output, arcsec)."""
    dt = solution.t - p.span.start
    omega_err = np.abs(solution.omega - exact.omega(dt)).max() / np.linalg.norm(p.body.omega0)
    attitude_err = quat_angle(solution.quaternion, exact.attitude(dt)) / ARCSEC
    comparison = {
        "regime": exact.regime,
        "period_d": exact.period,
        "two_T": exact.two_t,
        "k2": exact.m,
        OMEGA_MAX_REL_ERROR: float(omega_err),
        "attitude_max_error_vs_closed_form_arcsec": float(attitude_err.max()),
        ATTITUDE_MAX_ERROR_RAD: float(attitude_err.max() * ARCSEC),
    }
    return comparison, dt, attitude_err
