"""p95_near_principal_axis's comparison: the integrated pole's shift against Euler's pole rates of a symmetric
body spinning near its figure axis (P95, §843a; spinorbit.analysis.theory.pole_rates_symmetric)."""
import math

import numpy as np

# The metrics the verdict judges (the summary's comparison keys)
POLE_SHIFT_REL_ERROR, SPIN_REL_CHANGE = "pole_shift_rel_error", "spin_rel_change"


def compare(p, solution, u_euler):
    """(metrics, days from span.start, the pole's integrated (xi, eta) shift, Euler's), F along ``u_euler``
    in Euler's axes."""
    from ..analysis.theory import pole_rates_symmetric

    (cc, _, aa) = p.body.moments
    gamma, alpha, rho = p.body.spin, p.body.pole_offset, p.body.pole_angle
    dt = solution.t - p.span.start
    pole = solution.omega / np.linalg.norm(solution.omega, axis=1, keepdims=True)
    shift = pole[:, :2] - pole[0, :2]                              # (xi, eta) displacement of O
    d_alpha, alpha_d_rho = pole_rates_symmetric(aa, cc, gamma, p.orbit.gm, p.orbit.radius, rho, u_euler)
    rate = np.array([d_alpha * math.cos(rho) - alpha_d_rho * math.sin(rho),
                     d_alpha * math.sin(rho) + alpha_d_rho * math.cos(rho)])
    predicted = np.outer(dt, rate)
    error = np.linalg.norm(shift - predicted, axis=1).max() / np.linalg.norm(predicted[-1])
    comparison = {
        "d_alpha_dt_euler_rad_per_d": d_alpha,
        "alpha_d_rho_dt_euler_rad_per_d": alpha_d_rho,
        "pole_shift_integrated_rad": float(np.linalg.norm(shift[-1])),
        "pole_shift_euler_rad": float(np.linalg.norm(predicted[-1])),
        POLE_SHIFT_REL_ERROR: float(error),
        "free_rotation_over_torque_rate": float((aa - cc) / cc * gamma * alpha / np.linalg.norm(rate)),
        SPIN_REL_CHANGE: float(abs(np.linalg.norm(solution.omega[-1]) / gamma - 1)),
    }
    return comparison, dt, shift, predicted
