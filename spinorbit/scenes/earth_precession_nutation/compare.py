"""An Earth run against IAU 2006/2000A (ERFA): the residuals, the fitted precession and nutation, the non-rigid
layer applied and tabled, the full model's own checks, and the output table.

Edge module (astropy, ERFA through references.erfa_pole); the Earth scene declares, this compares.
"""

import numpy as np

from ... import nonrigid
from ...analysis.precession import compare_with_iau, fit_pole, free_nutation_amplitude, term_table
from ...bodies import earth
from ...constants import ARCSEC, JULIAN_CENTURY_D, MAS
from ...references import arguments, erfa_pole

# Nutation terms of the non-rigid table: name -> multipliers of (l, l', F, D, Om).
NONRIGID_TABLE_TERMS = {"18.6 yr": (0, 0, 0, 0, 1), "9.3 yr": (0, 0, 0, 0, 2), "1 yr": (0, 1, 0, 0, 0),
                        "0.5 yr": (0, 0, 2, -2, 2), "27.55 d": (1, 0, 0, 0, 0), "13.66 d": (0, 0, 2, 0, 2)}


def model_summary(moments, orbits, geodesic_arcsec_cy, j2_rate, j4):
    """The model's settings as the summary reports them."""
    error = getattr(orbits, "max_relative_error", None)
    return {"moments_over_C": (moments / moments[2]).tolist(), "bodies": list(orbits.names),
            "geodesic_precession_arcsec_cy": -geodesic_arcsec_cy if geodesic_arcsec_cy else 0.0,    # not -0.0
            "j2_rate_per_cy": earth.J2_RATE_PER_CY if j2_rate else 0.0, "j4": j4, "spin_rate_rad_d": earth.ERA_RATE_RAD_D,
            "orbit_interpolation_max_relative_error": None if error is None else error.tolist()}


def residuals(z, iau):
    """(dx, dy) mas and their rms/max: the figure axes ``z`` (n, 3, GCRS) minus the IAU CIP."""
    dx, dy = (z[:, 0] - iau["cip_x_rad"]) / MAS, (z[:, 1] - iau["cip_y_rad"]) / MAS
    return dx, dy, {"x_rms_mas": rms(dx), "x_max_mas": float(np.abs(dx).max()),
                    "y_rms_mas": rms(dy), "y_max_mas": float(np.abs(dy).max())}


def precession_nutation(t, z, iau):
    """(comparison, not_measured, nutation) on DE421: the fitted precession rate and main nutation terms
    against IAU 2006/2000A, and the model's nutation about its own mean pole (rad)."""
    offsets = erfa_pole.about_mean_pole(t, z)
    fitted, not_measured, mean = compare_with_iau(t, offsets, (iau["dpsi_rad"], iau["deps_rad"]), arguments.named(
        t, erfa_pole.NUTATION_ARGUMENTS), erfa_pole.IAU2000A_MAIN_ARCSEC)
    rate = fitted.pop("psi_rate_minus_iau_arcsec_cy")            # None over a short span, with why
    comparison = dict(psi_rate_minus_iau_arcsec_cy=rate, psi_A_rate_arcsec_cy=None if rate is None else
                      erfa_pole.PSI_A_RATE_ARCSEC_CY + rate, psi_A_rate_iau2006_arcsec_cy=erfa_pole.PSI_A_RATE_ARCSEC_CY,
                      **fitted)
    if rate is None:
        not_measured["comparison.psi_A_rate_arcsec_cy"] = not_measured["comparison.psi_rate_minus_iau_arcsec_cy"]
    nutation = {"psi_mean": iau["psi_bar_rad"] + mean[0], "eps_mean": iau["eps_a_rad"] + mean[1],
                "dpsi": offsets[0] - mean[0], "deps": offsets[1] - mean[1]}
    return comparison, not_measured, nutation


def torque_rates(t, poles, positions, gm, h_d=earth.H_D):
    """(dpsi/dt, deps/dt), "/cy, of the Fukushima-Williams angles of the axes ``poles`` (n, 3, GCRS) under the
    point masses' torque alone, H_d (T z) x z / omega (the axes held where they are: the first-order rate);
    ``positions``: per body (n, 3) km, geocentric GCRS; ``gm``: km^3/d^2 per body."""
    zdot = np.zeros_like(poles)
    for r, g in zip(positions, gm):
        dist = np.linalg.norm(r, axis=1)
        tz = (3.0 * g * np.einsum("ij,ij->i", r, poles) / dist**5)[:, None] * r
        zdot += h_d * np.cross(tz, poles) / earth.ERA_RATE_RAD_D
    plus, minus = erfa_pole.pole_angles(t, poles + zdot), erfa_pole.pole_angles(t, poles - zdot)
    return tuple((p - m) / 2.0 * JULIAN_CENTURY_D / ARCSEC for p, m in zip(plus, minus))


def nonrigid_pole(t, z):
    """Figure axes (n, 3) of the non-rigid Earth: the rigid nutation (x, y) = (dpsi sin eps_A, deps) about
    the IAU 2006 mean pole, times the transfer function term by term, plus MHB2000's nonlinear precession
    accumulated from the start (spinorbit.nonrigid)."""
    (dpsi, deps), sin_eps = erfa_pole.about_mean_pole(t, z), np.sin(erfa_pole.mean_angles(t)[3])
    x, y = nonrigid.nonrigid_nutation(t, dpsi * sin_eps, deps, *arguments.phases(t, nonrigid.LUNISOLAR_ARGUMENTS))
    return erfa_pole.from_mean_pole(t, x / sin_eps + nonrigid.nonlinear_precession(t - t[0]), y)


def nonrigid_summary(t, z_rigid, z, iau):
    """The rigid and non-rigid main terms beside IAU 2000A (mas), fitted alike on the nonrigid.LUNISOLAR_ARGUMENTS
    the run resolves (a term unresolved from a listed one is in it), the rigid residuals, the model's free modes."""
    terms = arguments.named(t, {str(m): m for m in nonrigid.LUNISOLAR_ARGUMENTS})
    series = {"rigid": erfa_pole.about_mean_pole(t, z_rigid), "nonrigid": erfa_pole.about_mean_pole(t, z),
              "iau2000a": (iau["dpsi_rad"], iau["deps_rad"])}
    cw, fcn = nonrigid.normal_modes()
    return {"rigid_x_rms_mas": rms((z_rigid[:, 0] - iau["cip_x_rad"]) / MAS),
            "rigid_y_rms_mas": rms((z_rigid[:, 1] - iau["cip_y_rad"]) / MAS),
            "terms_mas": term_table({name: fit_pole(t, *v, terms) for name, v in series.items()},
                                    {name: str(m) for name, m in NONRIGID_TABLE_TERMS.items()}),
            "nonlinear_precession_arcsec_cy": nonrigid.NONLINEAR_PRECESSION_ARCSEC_CY,
            "fcn_period_model_d": nonrigid.celestial_period_days(fcn),
            "fcn_period_mhb2000_d": nonrigid.celestial_period_days(nonrigid.PUBLISHED_FCN_CPSD),
            "chandler_period_model_d": nonrigid.wobble_period_days(cw),
            "chandler_period_mhb2000_d": nonrigid.wobble_period_days(nonrigid.PUBLISHED_CHANDLER_CPSD)}


def table(t, z, dx, dy, nutation):
    """The CIP X, Y and their residuals (mas); on DE421 the model's mean pole and nutation about it."""
    import astropy.units as u
    from astropy.table import QTable

    from ...schema import tdb_days_to_time

    columns = {"time": tdb_days_to_time(t), "cip_x": (z[:, 0] * u.rad).to(u.arcsec),
               "cip_y": (z[:, 1] * u.rad).to(u.arcsec), "cip_x_minus_erfa": dx * u.mas, "cip_y_minus_erfa": dy * u.mas}
    if nutation:
        columns.update({name: (nutation[key] * u.rad).to(unit) for name, key, unit in (
            ("precession_longitude", "psi_mean", u.arcsec), ("obliquity", "eps_mean", u.deg),
            ("nutation_longitude", "dpsi", u.arcsec), ("nutation_obliquity", "deps", u.arcsec))})
    return QTable(columns)


def full_checks(z_full, z_gyroscopic, t_dense, omega_dense, moments):
    """Full model: its agreement with the gyroscopic model (axes (n, 3) at the same times), and the amplitude
    of the free (Euler) nutation it started (body rates (m, 3) over ``t_dense``)."""
    diff = np.linalg.norm(z_full - z_gyroscopic, axis=1) / MAS
    return {"full_minus_gyroscopic_max_mas": float(diff.max()), "full_minus_gyroscopic_rms_mas": rms(diff),
            "free_nutation_amplitude_mas": free_nutation_amplitude(t_dense, omega_dense, moments) / MAS,
            "_full_minus_gyro_mas": diff}


def rms(x):
    return float(np.sqrt(np.mean(np.square(x))))
