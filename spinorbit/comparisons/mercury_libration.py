"""Mercury's 88-d libration in the 3:2 state (scenes/stress_mercury): the forced solution's linear theory (the
forcing's quadrature S_1 and the free-libration correction), Margot et al. (2007)'s series, and the terms
fitted to a run against them."""
import math

import numpy as np

from ..analysis.planar_spin_orbit import theta_from_quaternions
from ..analysis.spans import refusals, resolvable
from ..base.constants import ARCSEC
from ..plots.common import plot_series
from ..scene.declaration import Outcome

MARGOT_2007_ARCSEC = (35.8, 2.0)
HARMONICS = 6          # fitted harmonics of M; the initial rate sums the linear forced solution to k = 24
# comparison key -> the fitted term it comes from (k - 1 for the harmonic k, HARMONICS the free libration)
# The metrics the verdict judges (the summary's comparison keys)
LIBRATION_88D_REL_ERROR_VS_LINEAR = "libration_88d_rel_error_vs_linear"
LIBRATION_88D_REL_ERROR_VS_SERIES = "libration_88d_rel_error_vs_series"
FITTED_FROM = {"libration_88d_measured_arcsec": 0, LIBRATION_88D_REL_ERROR_VS_LINEAR: 0,
               LIBRATION_88D_REL_ERROR_VS_SERIES: 0, "libration_88d_cos_term_arcsec": 0, "passed": 0,
               "libration_44d_measured_arcsec": 1, "free_libration_fitted_arcsec": HARMONICS}


def design(t, n, w0, keep):
    """Columns [1, (sin kM, cos kM) for the harmonics k = 1..HARMONICS kept, sin w0 t, cos w0 t] with M = n t;
    t and t^2 in place of the free libration when the span cannot resolve it (``keep[-1]`` false)."""
    m = n * t
    columns = [np.ones_like(t)]
    for k in np.flatnonzero(keep[:-1]) + 1:
        columns += [np.sin(k * m), np.cos(k * m)]
    return np.column_stack(columns + ([np.sin(w0 * t), np.cos(w0 * t)] if keep[-1] else [t, t * t]))


def compare_run(p, run):
    """The 88-d term fitted to the run, against the linear forced solution and Margot et al. (2007)'s series."""
    import astropy.units as u

    solution, gamma, n, theory, e = run.solution, run.model.gamma, run.model.n, run.model.theory, p.orbit.e
    dt = solution.t - p.span.start
    lib = theta_from_quaternions(solution.quaternion) - 1.5 * n * dt
    w0 = theory["w0_over_n"] * n
    names = [f"{2 * math.pi / (k * n):.3g}-d term" for k in range(1, HARMONICS + 1)] + ["free libration"]
    keep = resolvable(np.append(n * np.arange(1, HARMONICS + 1), w0), abs(dt[-1]))
    columns = design(dt, n, w0, keep)
    coef = np.linalg.lstsq(columns, lib, rcond=None)[0]
    pairs = dict(zip(np.flatnonzero(keep[:-1]) + 1, coef[1:].reshape(-1, 2)))      # k -> (sin, cos)
    measured = math.copysign(math.hypot(*pairs[1]), pairs[1][0]) if 1 in pairs else None
    rel_linear = None if measured is None else measured / theory["amplitude_linear"] - 1
    rel_series = None if measured is None else measured / theory["amplitude_series"] - 1
    comparison = {
        "checks": "88-d (sin M) term of theta - 3/2 M fitted to the 3-D rigid body started in 3:2, vs the "
                  "linear forced solution (quadrature S_1, w0 correction) within stress.linear_rel_tol and "
                  "vs Margot et al. 2007's (3/2)(B-A)/C (1 - 11e^2 + 959e^4/48) within stress.series_rel_tol",
        "b_minus_a_over_c": gamma,
        "libration_88d_measured_arcsec": None if measured is None else measured / ARCSEC,
        "libration_88d_linear_theory_arcsec": theory["amplitude_linear"] / ARCSEC,
        "libration_88d_margot_series_arcsec": theory["amplitude_series"] / ARCSEC,
        LIBRATION_88D_REL_ERROR_VS_LINEAR: rel_linear,
        LIBRATION_88D_REL_ERROR_VS_SERIES: rel_series,
        "libration_88d_cos_term_arcsec": pairs[1][1] / ARCSEC if 1 in pairs else None,
        "libration_44d_measured_arcsec": float(math.hypot(*pairs[2]) / ARCSEC) if 2 in pairs else None,
        "libration_44d_linear_theory_arcsec": float(abs(theory["g"][1]) / ARCSEC),
        "free_libration_fitted_arcsec": float(math.hypot(coef[-2], coef[-1]) / ARCSEC) if keep[-1] else None,
        "free_libration_period_linear_yr": 2 * math.pi / w0 / 365.25,
        "S1_quadrature": theory["S1"], "S1_series_e4": 1 - 11 * e**2 + 959 * e**4 / 48,
        "H_quadrature": theory["H"],
        "margot_2007_radar_arcsec": MARGOT_2007_ARCSEC[0],
        "margot_2007_radar_sigma_arcsec": MARGOT_2007_ARCSEC[1],
        "margot_2007_radar_independent": False,
        "fit_residual_rms_arcsec": float(np.std(lib - columns @ coef) / ARCSEC),
        "passed": None if measured is None else bool(abs(rel_linear) < p.stress.linear_rel_tol
                                                     and abs(rel_series) < p.stress.series_rel_tol),
    }
    refused = refusals(names, np.append(n * np.arange(1, HARMONICS + 1), w0), abs(dt[-1]))
    not_measured = {f"comparison.{key}": f"not fitted: the {names[k]} {refused[names[k]]}"
                    for key, k in FITTED_FROM.items() if names[k] in refused}
    figures = {"libration": plot_series(dt[dt < 440], lib[dt < 440] / ARCSEC, "days from periapsis",
                                        "theta - 3/2 M [arcsec]")}
    return Outcome(comparison, {"libration": lib * u.rad}, figures, not_measured=not_measured)
