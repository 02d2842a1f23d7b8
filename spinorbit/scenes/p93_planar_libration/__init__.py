"""Planar libration on a circular orbit (Euler ch. 16 P93, §825-831) against its closed form.

The full 3-D rigid body turns about its axis C, normal to the orbit of the
centre of forces F (a uniform circle in the body's equatorial plane, the
inertial x-y plane).  zeta = AF = (longitude of F) - (longitude of A) obeys
zeta'' + n sin 2 zeta = 0 with n = (3/2) GM (B - A)/(C s^3); the scenario picks
Euler's energy constant C as a multiple of n (-1, 0, 1, > 1: §826's cases).
"""
import math

import numpy as np

from ...constants import ARCSEC
from ...models.assemblies.idealised import under_point_masses
from ...rotations import matrix_from_quat
from ...scene import Model, Outcome, Scene
from ...schema import DISTANCE, GM, RATE, Key
from ...verdict import Check, Verdict
from .. import common

SCHEMA = {
    "body.moments": Key(unit="", size=3, help="principal moments A < B <= C, any unit"),
    "orbit.gm": Key(**GM, help="GM of the centre of forces"),
    "orbit.radius": Key(**DISTANCE, help="distance s of F"),
    "orbit.rate": Key(**RATE, help="angular speed delta of F"),
    "libration.energy_over_n": Key(unit="", min=-1.0, max=1e6,
                                   help="Euler's constant C in units of n: -1, 0, 1 or > 1"),
}

_ZETA = "dop853 at rtol 1e-12 over 200 d: ~1e-4\" (tests/test_idealised_scenes.py)"


def verdict(p, comparison):
    """zeta against Euler's closed form; on the separatrix only while zeta < 80 deg (it is unstable)."""
    metric = ("zeta_error_max_arcsec_below_80deg" if p.libration.energy_over_n == 1
              else "zeta_error_max_arcsec")
    return Verdict("Euler's closed form (§826-831)", (Check("zeta", metric, 1e-3, "″", _ZETA),))


def planar_system(moments, orbit, t0, zeta0, zeta_dot0, delta):
    """Body turning about z with A at angle (delta t0 - zeta0) from x; omega_z = delta - zeta' (§825)."""
    lam = delta * t0 - zeta0
    q0 = np.array([math.cos(lam / 2), 0.0, 0.0, math.sin(lam / 2)])
    return under_point_masses(moments, orbit, q0, [0.0, 0.0, delta - zeta_dot0], t0, "planar libration")


def zeta_from_solution(solution, f_longitude):
    """zeta = longitude of F - longitude of the body's A axis, unwrapped (rad)."""
    lam = np.array([math.atan2(r[1, 0], r[0, 0]) for r in map(matrix_from_quat, solution.quaternion)])
    return np.unwrap(f_longitude - lam)


def crossing_times(t, x, level=0.0):
    """Times where x crosses ``level`` upwards, by linear interpolation."""
    i = np.nonzero((x[:-1] < level) & (x[1:] >= level))[0]
    return t[i] + (level - x[i]) * (t[i + 1] - t[i]) / (x[i + 1] - x[i])


def build(p, times):
    """The body on Euler's circle with zeta = 0 and zeta' from the energy constant; the closed form."""
    from ...orbits.analytic import CircularOrbits
    from ...theory import PlanarLibration, libration_n

    body = common.rigid_body(p)
    gm, s, delta = p.orbit.gm, p.orbit.radius, p.orbit.rate
    n = libration_n(body.moments, gm, s)
    zeta_dot0 = math.sqrt(max(p.libration.energy_over_n * n + n, 0.0))
    orbit = CircularOrbits(("F",), [gm], [s], [delta], phase=[-delta * p.t_start])
    return Model(planar_system(body.moments, orbit, p.t_start, 0.0, zeta_dot0, delta), n=n,
                 theory=PlanarLibration(n, 0.0, zeta_dot0))


def compare_run(p, run):
    solution, theory, n, delta = run.solution, run.model.theory, run.model.n, p.orbit.rate
    dt = solution.t - p.t_start
    zeta_num = zeta_from_solution(solution, delta * dt)
    zeta_cf = theory.zeta(dt)
    comparison = {"case": theory.case, "n_rad2_per_d2": n, "energy_over_n": theory.energy / n}
    not_measured = {}
    if theory.case == "separatrix":
        # Euler's t = ln tan(45 deg + zeta/2)/sqrt(2n); the separatrix is unstable, so compare while
        # zeta < 80 deg.
        keep = zeta_num < math.radians(80)
        comparison["zeta_error_max_arcsec_below_80deg"] = float(
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
        comparison["zeta_error_max_arcsec"] = float(np.abs(zeta_num - zeta_cf).max() / ARCSEC)
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

    figures = {"zeta": common.plot_series(dt, np.degrees([zeta_num, zeta_cf]), "days from start",
                                          "zeta = AF [deg]", ["integrated (3-D rigid body)", "closed form"])}
    columns = {"zeta": zeta_num * common.u().rad, "zeta_closed_form": zeta_cf * common.u().rad}
    return Outcome(comparison, columns, figures, not_measured=not_measured)


def _too_short(span_d, found, events, period_d):
    """Why a period cannot be measured: the span holds fewer than two of the events that bound one."""
    return (f"not measured: the {span_d:.6g} d span holds {found} {events}, two are needed; "
            f"the closed-form period is {period_d:.6g} d, so lengthen span.end beyond {2 * period_d:.6g} d")


SCENE = Scene(SCHEMA, build, compare_run, verdict, time_scales=common.rigid_body_time_scales(SCHEMA),
              taylor=True)
