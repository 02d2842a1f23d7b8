"""A coupled Earth-Moon run against DE421 and IAU 2006/2000A: the Moon's direction and range, the lunar pole
and longitude, the Earth's spin axis; and the tides' secular acceleration of the Moon (a run with the Earth's
tides minus one without).

Edge module (astropy units); the scene declares, this compares.
"""
import numpy as np

from ..analysis.librations import (
    LONGITUDE_ERROR_MAX_ARCSEC,
    LONGITUDE_ERROR_RMS_ARCSEC,
    POLE_ERROR_MAX_ARCSEC,
    POLE_ERROR_RMS_ARCSEC,
)
from ..base.constants import ARCSEC, JULIAN_CENTURY_D
from ..base.rotations import vector_angle

MAS = ARCSEC / 1000.0
# The metrics ``metrics`` computes (the summary's comparison keys, read by the verdict and the API)
MOON_DIRECTION_ERROR_MAX_ARCSEC, MOON_DIRECTION_ERROR_RMS_ARCSEC = ("moon_direction_error_max_arcsec",
                                                                    "moon_direction_error_rms_arcsec")
MOON_RANGE_ERROR_MAX_KM, MOON_RANGE_ERROR_RMS_KM = "moon_range_error_max_km", "moon_range_error_rms_km"
EARTH_AXIS_VS_CIP_MAX_MAS, EARTH_AXIS_VS_CIP_RMS_MAS = "earth_axis_vs_cip_max_mas", "earth_axis_vs_cip_rms_mas"
TIDAL_N_DOT_ARCSEC_PER_CY2, TIDAL_RECESSION_MM_PER_YR = "tidal_n_dot_arcsec_per_cy2", "tidal_recession_mm_per_yr"
AGAINST_DE421 = (MOON_DIRECTION_ERROR_MAX_ARCSEC, MOON_DIRECTION_ERROR_RMS_ARCSEC, MOON_RANGE_ERROR_MAX_KM,
                 MOON_RANGE_ERROR_RMS_KM, POLE_ERROR_MAX_ARCSEC, POLE_ERROR_RMS_ARCSEC, LONGITUDE_ERROR_MAX_ARCSEC,
                 LONGITUDE_ERROR_RMS_ARCSEC)


def covered(t):
    """The outputs DE421 has data at (its lunar series, 1899-12-04 to 2200-02-01 TDB; its orbits reach as
    far)."""
    from ..bodies.de421_orientation import span

    first, last = span()
    return (t >= first) & (t <= last)


def orbit_errors(t, r):
    """(direction (rad), range (km)) of the integrated geocentric Moon r (n, 3) against DE421's at TDB days t,
    NaN where DE421 has no data."""
    from ..orbits.kernel import open_ephemeris

    direction, distance, inside = np.full(len(t), np.nan), np.full(len(t), np.nan), covered(t)
    if inside.any():
        ephemeris = open_ephemeris("de421", t[inside].min(), t[inside].max())
        de421, _ = ephemeris.relative_states("moon", "earth", t[inside])
        direction[inside] = vector_angle(r[inside], de421)
        distance[inside] = np.linalg.norm(r[inside], axis=1) - np.linalg.norm(de421, axis=1)
    return direction, distance


def earth_axis_error(t, axis):
    """Angle (rad) of the Earth's spin axis (n, 3) from the IAU 2006/2000A CIP (ERFA) at TDB days t."""
    from ..references.erfa_pole import cip_vector

    return vector_angle(axis, cip_vector(t))


def metrics(t, direction, distance, lunar, earth_axis):
    """(the summary's comparison: max and rms of each error, in arcsec, km and mas, over the outputs DE421 has
    data at; {metric: why not measured} where it has none)."""
    inside = covered(t)
    if not inside.any():
        from ..base.errors import tdb_dates

        why = ("DE421's lunar series covers 1899-12-04 to 2200-02-01 TDB; "
               f"the span is {tdb_dates((t[0], t[-1]))}")
        return _axis_metrics(earth_axis), {f"comparison.{name}": why for name in AGAINST_DE421}
    direction, distance = direction[inside], distance[inside]
    out = {MOON_DIRECTION_ERROR_MAX_ARCSEC: float(direction.max() / ARCSEC),
           MOON_DIRECTION_ERROR_RMS_ARCSEC: float(np.sqrt(np.mean(direction ** 2)) / ARCSEC),
           MOON_RANGE_ERROR_MAX_KM: float(np.abs(distance).max()),
           MOON_RANGE_ERROR_RMS_KM: float(np.sqrt(np.mean(distance ** 2)))}
    out.update(lunar)
    out.update(_axis_metrics(earth_axis))
    return out, {}


def _axis_metrics(earth_axis):
    """The Earth's axis against the CIP (rad, (n,)): its max and rms, mas."""
    return {EARTH_AXIS_VS_CIP_MAX_MAS: float(earth_axis.max() / MAS),
            EARTH_AXIS_VS_CIP_RMS_MAS: float(np.sqrt(np.mean(earth_axis ** 2)) / MAS)}


def tidal_acceleration(t, r_on, r_off, v_off):
    """The Moon's secular acceleration from the Earth's tides: the geocentric Moon r (n, 3) of a run with
    them and r, v of one without, at TDB days t.

    n_dot: the longitude difference dl (in the orbit plane) fitted by c0 + c1 T + n_dot T^2 / 2, T in
    centuries from the start.  Recession: the distance difference taken at the same phase of the Moon (the
    run without tides dl/w later, w its angular rate: dr - dl r'/w), which removes the monthly terms the
    phase difference shifts (1 km by the end of a century, against the 4 m sought), fitted by d0 + a_dot T.
    {tidal_n_dot "/cy^2, tidal_recession (a_dot) mm/yr, both fits' rms residuals, the span}."""
    distance_off = np.linalg.norm(r_off, axis=1)
    plane = np.cross(r_off, v_off)
    rate = np.linalg.norm(plane, axis=1) / distance_off ** 2
    plane /= np.linalg.norm(plane, axis=1)[:, None]
    longitude = np.arctan2(np.sum(np.cross(r_off, r_on) * plane, axis=1), np.sum(r_off * r_on, axis=1))
    radial_rate = np.sum(r_off * v_off, axis=1) / distance_off
    distance = np.linalg.norm(r_on, axis=1) - distance_off - longitude / rate * radial_rate
    big_t = (t - t[0]) / JULIAN_CENTURY_D
    lon_fit = np.polynomial.polynomial.polyfit(big_t, longitude / ARCSEC, 2)
    r_fit = np.polynomial.polynomial.polyfit(big_t, distance, 1)
    residual = lambda fit, y: float(np.sqrt(np.mean((np.polynomial.polynomial.polyval(big_t, fit) - y) ** 2)))
    return {TIDAL_N_DOT_ARCSEC_PER_CY2: float(2.0 * lon_fit[2]), TIDAL_RECESSION_MM_PER_YR: float(r_fit[1] * 1e4),
            "tidal_longitude_fit_rms_arcsec": residual(lon_fit, longitude / ARCSEC),
            "tidal_distance_fit_rms_km": residual(r_fit, distance), "tidal_span_yr": float(big_t[-1] * 100.0)}


def lunar_errors(t, q):
    """(ICRF-to-body matrices, DE421's provenance, pole and longitude differences (rad, NaN where DE421 has no
    data), their metrics) of the Moon's attitudes q (n, 4)."""
    from ..analysis.librations import icrf_to_body, pole_and_longitude_difference, residual_metrics
    from ..references.moon_de421 import Orientation, provenance

    mats, inside = icrf_to_body(q), covered(t)
    pole, longitude, metrics_ = np.full(len(t), np.nan), np.full(len(t), np.nan), {}
    if inside.any():
        de421 = Orientation()(t[inside])["icrf_to_body"]
        pole[inside], longitude[inside] = pole_and_longitude_difference(mats[inside], de421)
        metrics_ = residual_metrics(mats[inside], de421)
    return mats, provenance(), pole, longitude, metrics_


def table(t, r, mats, errors, earth_axis):
    """The run's table: the geocentric Moon (km, ICRF) and its errors, the JPL angles (rad) and the lunar
    pole and longitude errors, the Earth's axis (ICRF) and its angle from the CIP.  errors: {name: array} in
    rad/km."""
    import astropy.units as u
    from astropy.table import QTable

    from ..base.rotations import euler313_from_matrix
    from ..scene.schema import tdb_days_to_time

    out = QTable()
    out["time"] = tdb_days_to_time(t)
    for k, axis in enumerate("xyz"):
        out[f"moon_geocentric_{axis}"] = r[:, k] * u.km
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
