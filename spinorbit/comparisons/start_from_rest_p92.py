"""p92_start_from_rest's comparison: the integrator's first step against Euler's first motion of a body at rest
(P92, §820-823; spinorbit.analysis.theory.start_from_rest): omega(t)/t's axis and rate."""
import math

import numpy as np

from ..base.constants import ARCSEC

# The metrics the verdict judges (the summary's comparison keys)
AXIS_ERROR_ARCSEC, RATE_REL_ERROR = "axis_error_arcsec", "rate_rel_error"


def compare(p, solution, direction):
    """The metrics of the first output step against Euler's axis and rate, F at body ``direction``."""
    from ..analysis.theory import start_from_rest

    axis, cos_of, rate = start_from_rest(p.body.moments, direction, p.orbit.gm, p.orbit.radius)
    dt1 = solution.t[1] - solution.t[0]
    w1 = solution.omega[1]
    axis_num = w1 / np.linalg.norm(w1)
    return {
        "axis_cos_alpha": float(axis[0]), "axis_cos_beta": float(axis[1]), "axis_cos_gamma": float(axis[2]),
        "cos_OF": cos_of,
        "rate_euler_rad_per_d2": rate,
        "rate_integrated_rad_per_d2": float(np.linalg.norm(w1) / dt1),
        RATE_REL_ERROR: float(abs(np.linalg.norm(w1) / dt1 / rate - 1)),
        # atan2 of |a x b| and a.b: acos(a.b) floors at sqrt(2 eps) = 0.003" near zero
        AXIS_ERROR_ARCSEC: float(
            math.atan2(np.linalg.norm(np.cross(axis_num, axis)), axis_num @ axis) / ARCSEC),
        "first_step_d": float(dt1),
    }
