"""p94_forced_libration's comparison: the integrated libration zeta = AF against Euler's forced libration to
first and second order (P94, §835; spinorbit.analysis.theory.forced_libration)."""
import numpy as np

from ..analysis.planar_libration import zeta_from_solution
from ..base.constants import ARCSEC

ZETA_ERROR_SECOND_ORDER_REL = "zeta_error_second_order_rel"        # the metric the verdict judges


def compare(p, solution, n):
    """(metrics, days from span.start, the integrated zeta, Euler's to second order), zeta in rad; ``n`` the
    libration's n (rad^2/d^2)."""
    from ..analysis.theory import forced_libration

    o, dt = p.orbit, solution.t - p.span.start
    zeta_num = zeta_from_solution(solution, o.rate * dt + o.alpha * np.sin(o.frequency * dt))
    zeta_first = forced_libration(dt, n, o.frequency, o.alpha)
    zeta_second = forced_libration(dt, n, o.frequency, o.alpha, o.beta)
    amplitude = o.frequency**2 * o.alpha / (o.frequency**2 - 2 * n)
    comparison = {
        "n_rad2_per_d2": n,
        "amplitude_euler_arcsec": amplitude / ARCSEC,
        "amplitude_measured_arcsec": float(np.abs(zeta_num).max() / ARCSEC),
        "zeta_error_first_order_max_arcsec": float(np.abs(zeta_num - zeta_first).max() / ARCSEC),
        "zeta_error_second_order_max_arcsec": float(np.abs(zeta_num - zeta_second).max() / ARCSEC),
        ZETA_ERROR_SECOND_ORDER_REL: float(np.abs(zeta_num - zeta_second).max() / abs(amplitude)),
    }
    return comparison, dt, zeta_num, zeta_second
