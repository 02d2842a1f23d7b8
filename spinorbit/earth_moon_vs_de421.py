"""A coupled Earth-Moon run against DE421 and IAU 2006/2000A: the Moon's direction and range, the lunar pole
and longitude, the Earth's spin axis; and the tides' secular acceleration of the Moon (a run with the Earth's
tides minus one without).

Edge module (astropy units); the scene declares, this compares.
"""
import numpy as np

from .constants import ARCSEC, JULIAN_CENTURY_D

MAS = ARCSEC / 1000.0


def orbit_errors(t, states):
    """(direction (rad), range (km)) of the integrated geocentric Moon against DE421's at TDB days t."""
    from .orbits.kernel import open_ephemeris

    de421, _ = open_ephemeris("de421", t[0], t[-1]).relative_states("moon", "earth", t)
    r = states[:, 0:3]
    cross = np.linalg.norm(np.cross(r, de421), axis=1)
    return np.arctan2(cross, np.sum(r * de421, axis=1)), np.linalg.norm(r, axis=1) - np.linalg.norm(de421, axis=1)


def earth_axis_error(t, axis):
    """Angle (rad) of the Earth's spin axis (n, 3) from the IAU 2006/2000A CIP (ERFA) at TDB days t."""
    from .references.erfa_pole import cip_vector

    cip = cip_vector(t)
    return np.arctan2(np.linalg.norm(np.cross(axis, cip), axis=1), np.sum(axis * cip, axis=1))


def metrics(direction, distance, lunar, earth_axis):
    """The summary's comparison: max and rms of each error, in arcsec, km and mas."""
    out = {"moon_direction_error_max_arcsec": float(direction.max() / ARCSEC),
           "moon_direction_error_rms_arcsec": float(np.sqrt(np.mean(direction ** 2)) / ARCSEC),
           "moon_range_error_max_km": float(np.abs(distance).max()),
           "moon_range_error_rms_km": float(np.sqrt(np.mean(distance ** 2)))}
    out.update(lunar)
    out["earth_axis_vs_cip_max_mas"] = float(earth_axis.max() / MAS)
    out["earth_axis_vs_cip_rms_mas"] = float(np.sqrt(np.mean(earth_axis ** 2)) / MAS)
    return out


def tidal_acceleration(t, with_tides, without):
    """The Moon's secular acceleration from the Earth's tides: two runs' states (n, 19) at TDB days t.

    The longitude difference (in the orbit plane) is fitted by c0 + c1 T + n_dot T^2 / 2 and the difference of
    the osculating semi-major axes (vis-viva, GM of the Earth and the Moon) by d0 + a_dot T, T in centuries
    from the start: {n_dot "/cy^2, a_dot mm/yr, the fits' rms residuals}."""
    from .bodies.de421_header import gm_km3_d2

    gm = gm_km3_d2("earth") + gm_km3_d2("moon")
    r_on, r_off = with_tides[:, 0:3], without[:, 0:3]
    plane = np.cross(r_off, without[:, 3:6])
    plane /= np.linalg.norm(plane, axis=1)[:, None]
    longitude = np.arctan2(np.sum(np.cross(r_off, r_on) * plane, axis=1), np.sum(r_off * r_on, axis=1))
    semi_major = [1.0 / (2.0 / np.linalg.norm(s[:, 0:3], axis=1) - np.sum(s[:, 3:6] ** 2, axis=1) / gm)
                  for s in (with_tides, without)]
    big_t = (t - t[0]) / JULIAN_CENTURY_D
    lon_fit = np.polynomial.polynomial.Polynomial.fit(big_t, longitude / ARCSEC, 2, window=[0, 1], domain=[0, 1])
    a_fit = np.polynomial.polynomial.Polynomial.fit(big_t, semi_major[0] - semi_major[1], 1, window=[0, 1],
                                                    domain=[0, 1])
    return {"n_dot_arcsec_per_cy2": float(2.0 * lon_fit.coef[2]),
            "recession_mm_per_yr": float(a_fit.coef[1] * 1e6 / 100.0),
            "longitude_fit_rms_arcsec": float(np.sqrt(np.mean((lon_fit(big_t) - longitude / ARCSEC) ** 2))),
            "semi_major_fit_rms_km": float(np.sqrt(np.mean((a_fit(big_t) - semi_major[0] + semi_major[1]) ** 2))),
            "span_yr": float(big_t[-1] * 100.0)}


def lunar_errors(t, states):
    """(ICRF-to-body matrices, DE421's, pole and longitude differences (rad), their metrics) of the Moon."""
    from .analysis.librations import icrf_to_body, pole_and_longitude_difference, residual_metrics
    from .references.moon_de421 import Orientation

    mats = icrf_to_body(states[:, 6:10])
    de421 = Orientation()(t)
    pole, longitude = pole_and_longitude_difference(mats, de421["icrf_to_body"])
    return mats, de421, pole, longitude, residual_metrics(mats, de421["icrf_to_body"])


def table(t, states, mats, errors, earth_axis):
    """The run's table: the geocentric Moon (km, ICRF) and its errors, the JPL angles (rad) and the lunar pole
    and longitude errors, the Earth's axis (ICRF) and its angle from the CIP.  errors: {name: array} in rad/km."""
    import astropy.units as u
    from astropy.table import QTable

    from .rotations import euler313_from_matrix
    from .schema import tdb_days_to_time

    out = QTable()
    out["time"] = tdb_days_to_time(t)
    for k, axis in enumerate("xyz"):
        out[f"moon_geocentric_{axis}"] = states[:, k] * u.km
    for name, column in zip(("phi", "theta", "psi"), euler313_from_matrix(mats).T):
        out[name] = column * u.rad
    out["moon_direction_error"] = errors["direction"] / ARCSEC * u.arcsec
    out["moon_range_error"] = errors["range"] * u.km
    out["pole_error"] = errors["pole"] / ARCSEC * u.arcsec
    out["longitude_error"] = errors["longitude"] / ARCSEC * u.arcsec
    for k, axis in enumerate("xyz"):
        out[f"earth_axis_{axis}"] = earth_axis[:, k]
    out["earth_axis_minus_cip"] = errors["earth_axis"] / MAS * u.mas
    return out
