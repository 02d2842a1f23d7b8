"""A planar libration run (scenes/p93_planar_libration) against Euler's closed form (§826-831, theory.
PlanarLibration): zeta's error, and per case the time to the separatrix's angles, the period, the largest
digression, the return time or the half-turn time, measured beside Euler's."""
import math

import numpy as np

from ..analysis.planar_libration import crossing_times, zeta_from_solution
from ..base.constants import ARCSEC
from ..plots.common import plot_series
from ..scene.declaration import Outcome

# The metrics the verdict judges (the summary's comparison keys): zeta's error, on the separatrix below 80 deg
ZETA_ERROR_MAX_ARCSEC, ZETA_ERROR_MAX_ARCSEC_BELOW_80DEG = "zeta_error_max_arcsec", "zeta_error_max_arcsec_below_80deg"


def compare_run(p, run):
    """zeta against Euler's closed form for the energy constant's case: the error, and the times, periods and
    digressions measured beside Euler's."""
    import astropy.units as u

    solution, theory, n, delta = run.solution, run.model.theory, run.model.n, p.orbit.rate
    dt = solution.t - p.span.start
    zeta_num = zeta_from_solution(solution, delta * dt)
    zeta_cf = theory.zeta(dt)
    comparison = {"case": theory.case, "n_rad2_per_d2": n, "energy_over_n": theory.energy / n}
    not_measured = {}
    if theory.case == "separatrix":
        # Euler's t = ln tan(45 deg + zeta/2)/sqrt(2n); the separatrix is unstable, so compare while
        # zeta < 80 deg.
        keep = zeta_num < math.radians(80)
        comparison[ZETA_ERROR_MAX_ARCSEC_BELOW_80DEG] = float(
            np.abs(zeta_num - zeta_cf)[keep].max() / ARCSEC)
        for deg in (30, 60, 80):
            reached = crossing_times(dt, zeta_num, math.radians(deg))
            comparison[f"time_to_{deg}deg_d"] = float(reached[0]) if reached.size else None
            if not reached.size:
                not_measured[f"comparison.time_to_{deg}deg_d"] = (
                    f"not measured: zeta does not reach {deg} deg within the {dt[-1]:.6g} d span; "
                    f"Euler's time is {theory.separatrix_time(math.radians(deg)):.6g} d, "
                    "so lengthen span.end")
            comparison[f"time_to_{deg}deg_euler_d"] = float(theory.separatrix_time(math.radians(deg)))
    else:
        comparison[ZETA_ERROR_MAX_ARCSEC] = float(np.abs(zeta_num - zeta_cf).max() / ARCSEC)
    if theory.case == "bounded":
        ups = crossing_times(dt, zeta_num)
        comparison["period_closed_form_d"] = float(theory.period)
        comparison["period_measured_d"] = float(np.mean(np.diff(ups))) if ups.size > 1 else None
        if ups.size < 2:
            not_measured["comparison.period_measured_d"] = _too_short(
                dt[-1], ups.size, "upward zero crossings of zeta", theory.period)
        comparison["max_digression_closed_form_deg"] = math.degrees(theory.max_digression)
        comparison["max_digression_measured_deg"] = float(np.degrees(np.abs(zeta_num).max()))
        comparison["return_time_small_oscillation_euler_d"] = theory.small_oscillation_return_time()
        comparison["return_time_exact_d"] = float(theory.period / 2)
    if theory.case == "circulation":
        levels = math.pi / 2 + math.pi * np.arange(int((zeta_num.max() - math.pi / 2) // math.pi) + 1)
        passes = np.interp(levels, zeta_num, dt)
        comparison["half_turn_time_closed_form_d"] = float(theory.period)
        comparison["half_turn_time_measured_d"] = float(np.mean(np.diff(passes))) if passes.size > 1 else None
        if passes.size < 2:
            not_measured["comparison.half_turn_time_measured_d"] = _too_short(
                dt[-1], passes.size, "passes of zeta through 90 deg + k 180 deg", theory.period)
    if theory.case == "equilibrium":
        comparison["max_digression_measured_arcsec"] = float(np.abs(zeta_num).max() / ARCSEC)

    figures = {"zeta": plot_series(dt, np.degrees([zeta_num, zeta_cf]), "days from start",
                                          "zeta = AF [deg]", ["integrated (3-D rigid body)", "closed form"])}
    columns = {"zeta": zeta_num * u.rad, "zeta_closed_form": zeta_cf * u.rad}
    return Outcome(comparison, columns, figures, not_measured=not_measured)


def _too_short(span_d, found, events, period_d):
    """Why a period cannot be measured: the span holds fewer than two of the events that bound one."""
    return (f"not measured: the {span_d:.6g} d span holds {found} {events}, two are needed; "
            f"the closed-form period is {period_d:.6g} d, so lengthen span.end beyond {2 * period_d:.6g} d")
