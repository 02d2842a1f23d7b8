"""An Earth run against IAU 2006/2000A (ERFA): the residuals, the fitted precession and nutation, the full
model's own checks, and the output table (the non-rigid layer and its references: earth_nonrigid.py).

Edge module (astropy, ERFA through references.erfa_pole); the Earth scene declares, this compares.
"""

import numpy as np

from ..analysis.precession import PSI_RATE_MINUS_IAU_ARCSEC_CY, compare_with_iau, free_nutation_amplitude
from ..base.constants import MAS
from ..bodies import earth
from ..references import arguments, erfa_pole

# The metrics ``residuals`` and ``full_checks`` compute (the summary's comparison keys, read by the verdict and the
# API)
X_RMS_MAS, Y_RMS_MAS = "x_rms_mas", "y_rms_mas"
FULL_MINUS_GYROSCOPIC_MAX_MAS = "full_minus_gyroscopic_max_mas"

def geodesic_arcsec_cy(p):
    """De Sitter's precession the model holds ("/cy), or 0 without it (earth.geodesic_precession)."""
    return earth.GEODESIC_PRECESSION_ARCSEC_CY if p.earth.geodesic_precession else 0.0


def poles(p, t, system, y):
    """(the rigid model's figure axis at t, tilted by the tides' secular rates; the pole compared: that, with
    earth.nonrigid the non-rigid Earth's response applied (comparisons.earth_nonrigid); IAU 2006/2000A's pole
    at t; the non-rigid settings, or False)."""
    from ..starts import earth_tides as tides
    from . import earth_nonrigid as nr

    z = system.figure_axes("earth", t, y)
    z = z_rigid = tides.tilted(t, z, *tides.rates(p.earth.tides, p.orbit.source))
    iau, nonrigid = erfa_pole.IauPole()(t), p.earth.nonrigid and nr.settings(p)
    z = nr.nonrigid_pole(t, z, **nonrigid) if nonrigid else z
    return z_rigid, z, iau, nonrigid


def p96_rate(p, t, z, model, moments):
    """Euler's P96 rate beside the model's (references.euler_p96.compare): (metrics, not measured); ``model``
    the scene's (its ecliptic pole, and the plane's tilt on a circular orbit)."""
    from ..references import euler_p96

    return euler_p96.compare(t, z, model.pole_ecl, moments / moments[2], earth.ERA_RATE_RAD_D,
                             model.plane_tilt is not None, geodesic_arcsec_cy(p))


def model_summary(moments, orbits, geodesic_arcsec_cy, j2_rate, j4):
    """The model's settings as the summary reports them."""
    error = getattr(orbits, "max_relative_error", None)
    return {"moments_over_C": (moments / moments[2]).tolist(), "bodies": list(orbits.names),
            "geodesic_precession_arcsec_cy": -geodesic_arcsec_cy if geodesic_arcsec_cy else 0.0,    # not -0.0
            "j2_rate_per_cy": earth.J2_RATE_PER_CY if j2_rate else 0.0, "j4": j4,
            "spin_rate_rad_d": earth.ERA_RATE_RAD_D,
            "orbit_interpolation_max_relative_error": None if error is None else error.tolist()}


def residuals(z, iau):
    """(dx, dy) mas and their rms/max: the figure axes ``z`` (n, 3, GCRS) minus the IAU CIP."""
    dx, dy = (z[:, 0] - iau["cip_x_rad"]) / MAS, (z[:, 1] - iau["cip_y_rad"]) / MAS
    return dx, dy, {X_RMS_MAS: rms(dx), "x_max_mas": float(np.abs(dx).max()),
                    Y_RMS_MAS: rms(dy), "y_max_mas": float(np.abs(dy).max())}


def precession_nutation(t, z, iau):
    """(comparison, not_measured, nutation) on DE421: the fitted precession rate and main nutation terms
    against IAU 2006/2000A, and the model's nutation about its own mean pole (rad)."""
    offsets = erfa_pole.about_mean_pole(t, z)
    fitted, not_measured, mean = compare_with_iau(
        t, offsets, (iau["dpsi_rad"], iau["deps_rad"]), arguments.named(t, erfa_pole.NUTATION_ARGUMENTS),
        erfa_pole.IAU2000A_MAIN_ARCSEC)
    rate = fitted.pop(PSI_RATE_MINUS_IAU_ARCSEC_CY)            # None over a short span, with why
    comparison = {PSI_RATE_MINUS_IAU_ARCSEC_CY: rate,
                  "psi_A_rate_arcsec_cy": None if rate is None else erfa_pole.PSI_A_RATE_ARCSEC_CY + rate,
                  "psi_A_rate_iau2006_arcsec_cy": erfa_pole.PSI_A_RATE_ARCSEC_CY,
                  **fitted}
    if rate is None:
        not_measured["comparison.psi_A_rate_arcsec_cy"] = (
            not_measured[f"comparison.{PSI_RATE_MINUS_IAU_ARCSEC_CY}"])
    nutation = {"psi_mean": iau["psi_bar_rad"] + mean[0], "eps_mean": iau["eps_a_rad"] + mean[1],
                "dpsi": offsets[0] - mean[0], "deps": offsets[1] - mean[1]}
    return comparison, not_measured, nutation



def table(t, z, dx, dy, nutation):
    """The CIP X, Y and their residuals (mas); on DE421 the model's mean pole and nutation about it."""
    import astropy.units as u
    from astropy.table import QTable

    from ..scene.schema import tdb_days_to_time

    columns = {"time": tdb_days_to_time(t), "cip_x": (z[:, 0] * u.rad).to(u.arcsec),
               "cip_y": (z[:, 1] * u.rad).to(u.arcsec), "cip_x_minus_erfa": dx * u.mas,
               "cip_y_minus_erfa": dy * u.mas}
    if nutation:
        columns.update({name: (nutation[key] * u.rad).to(unit) for name, key, unit in (
            ("precession_longitude", "psi_mean", u.arcsec), ("obliquity", "eps_mean", u.deg),
            ("nutation_longitude", "dpsi", u.arcsec), ("nutation_obliquity", "deps", u.arcsec))})
    return QTable(columns)


def full_checks(z_full, z_gyroscopic, t_dense, omega_dense, moments):
    """Full model: its agreement with the gyroscopic model (axes (n, 3) at the same times), and the amplitude
    of the free (Euler) nutation it started (body rates (m, 3) over ``t_dense``)."""
    diff = np.linalg.norm(z_full - z_gyroscopic, axis=1) / MAS
    return {FULL_MINUS_GYROSCOPIC_MAX_MAS: float(diff.max()), "full_minus_gyroscopic_rms_mas": rms(diff),
            "free_nutation_amplitude_mas": free_nutation_amplitude(t_dense, omega_dense, moments) / MAS,
            "_full_minus_gyro_mas": diff}


def rms(x):
    return float(np.sqrt(np.mean(np.square(x))))


def full_model_checks(p, run, twin, z_full):
    """The full model of ``run`` (spinorbit.scene.declaration.Run) against its gyroscopic ``twin`` on the same
    orbits and start (start.gyroscopic_twin), and the free nutation it started (a dense run over
    ``comparison.free_nutation_span``)."""
    t, t0, system = run.times, p.span.start, run.model.system
    twin_run, _ = run.integrate(twin, t, "gyroscopic twin", "rk8", {"step": p.comparison.gyroscopic_step})
    t_dense = t0 + np.arange(0.0, min(p.comparison.free_nutation_span, t[-1] - t0), 0.125)
    dense, _ = run.integrate(system, t_dense, "free nutation", estimate_error=False)
    return full_checks(z_full, twin.figure_axes("earth", t, twin_run.y), t_dense, dense.omega,
                       system.bodies["earth"].figure.moments)
