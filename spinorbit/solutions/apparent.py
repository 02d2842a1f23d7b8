"""The Moon seen from a place on the Earth: its apparent place (light time and aberration, as skyfield's
``observe().apparent()`` makes it), the sub-observer point in the lunar frame at the time the light left the
Moon, and the position angle of the Moon's axis on the sky.

The observer's GCRS position and velocity are astropy's (``EarthLocation.get_gcrs_posvel``: ERFA's Earth
rotation with UT1 - UTC and polar motion from astropy's IERS tables, ``astropy.utils.iers``; a date they do not
cover is refused, not extrapolated); the Earth's and the Moon's barycentric positions are the JPL ephemeris the
Moon's solution runs on (their light time iterated: the Moon at t - lt, the observer at t); aberration is
ERFA's ``ab`` (SOFA's iauAb: the observer's barycentric velocity to second order in v/c, with the Sun's
potential at the observer's distance from it).  Gravitational light deflection is left out: the Sun's bends the Moon's
light by ~5 uas (the Moon and the observer are both ~1 au from it, and their difference is what deflects), the
Earth's by at most ~0.3 mas.  The axis's position angle is measured from the north of the true equator of date
(IAU 2006/2000A's CIP, ERFA ``pnm06a``) eastward, as the almanacs give P.
"""
import numpy as np

from ..base.errors import InputError

C_KM_D = 299_792.458 * 86_400.0       # km per day
AU_KM = 149_597_870.7
LIGHT_TIME_ITERATIONS = 3             # each multiplies the error by v/c ~ 1e-4: 1.3 s of light time to 1e-12 s


def earth_orientation_checked(when):
    """Refuse (InputError on ``times``) dates for which astropy's IERS tables hold no UT1 - UTC (astropy would
    clamp them to its table's ends) or only predictions it calls stale."""
    from astropy.utils import iers

    table = iers.earth_orientation_table.get()
    try:
        _, status = table.ut1_utc(when.utc, return_status=True)
    except ValueError as exc:
        raise InputError("times", _span_said(when), "dates whose UT1 astropy's IERS tables hold (for an observer; "
                         f"astropy: {str(exc).splitlines()[0]}): download a newer IERS-A table or set "
                         "astropy.utils.iers.conf.auto_max_age") from None
    outside = np.atleast_1d(status) < 0
    if outside.any():
        from astropy.time import Time

        held = Time([table["MJD"][0].value, table["MJD"][-1].value], format="mjd", scale="utc").iso
        raise InputError("times", _span_said(when[outside]),
                         f"dates whose UT1 astropy's IERS tables hold (for an observer: {held[0][:10]} to "
                         f"{held[1][:10]} UTC); 1 s of UT1 moves the sub-observer point by ~0.25\"")


def _span_said(when):
    iso = when.utc.iso if when.size == 1 else np.array([when.utc.min().iso, when.utc.max().iso])
    return f"{when.size} date(s), {' to '.join(np.atleast_1d(iso))} UTC"


def moon_seen_from(observer, when, t, source):
    """{"light_time_d" (n,), "apparent" (n, 3) unit vectors GCRS} of the Moon seen from ``observer``
    (EarthLocation) at ``when`` (Time, n) = TDB days ``t``, on the ephemeris ``source`` (a JPL kernel); the
    dates are those :func:`earth_orientation_checked` lets through."""
    import astropy.units as u
    import erfa

    from ..orbits import kernel

    position, velocity = observer.get_gcrs_posvel(when)
    obs_p, obs_v = position.xyz.to_value(u.km).T, velocity.xyz.to_value(u.km / u.day).T
    ephemeris = kernel.open_ephemeris(source, t.min() - 1.0, t.max() + 1.0)
    earth_p, earth_v = ephemeris.relative_states("earth", "solar_system_barycenter", t)
    sun_p, _ = ephemeris.relative_states("sun", "earth", t)
    light_time = np.zeros_like(t)
    for _ in range(LIGHT_TIME_ITERATIONS):
        emitted = t - light_time
        moon_p, _ = ephemeris.relative_states("moon", "solar_system_barycenter", emitted)
        r = moon_p - earth_p - obs_p
        light_time = np.linalg.norm(r, axis=1) / C_KM_D
    beta = (earth_v + obs_v) / C_KM_D
    apparent = erfa.ab(r / np.linalg.norm(r, axis=1, keepdims=True), beta,
                       np.linalg.norm(sun_p - obs_p, axis=1) / AU_KM, np.sqrt(1.0 - np.sum(beta ** 2, axis=1)))
    return {"light_time_d": light_time, "apparent": apparent}


def axis_position_angle(when, apparent, axis):
    """The position angle (rad, 0 to 2 pi) of the body's axis ``axis`` (n, 3, GCRS) on the sky at the apparent
    directions ``apparent`` (n, 3): from the north of the true equator of date eastward."""
    import erfa

    tt = when.tt
    to_date = erfa.pnm06a(tt.jd1, tt.jd2)
    u = np.einsum("nij,nj->ni", to_date, apparent)
    a = np.einsum("nij,nj->ni", to_date, axis)
    east = np.cross([0.0, 0.0, 1.0], u)
    east /= np.linalg.norm(east, axis=1, keepdims=True)
    north = np.cross(u, east)
    return np.arctan2(np.sum(a * east, axis=1), np.sum(a * north, axis=1)) % (2 * np.pi)


def observed(solution, t, when, source, observer, frame):
    """The observer's columns at TDB days ``t`` (= ``when``): the sub-observer longitude and latitude (rad) in
    ``frame`` (tables.FRAMES) of the lunar frame at the light's departure, and the axis's position angle (rad)."""
    from ..analysis.librations import icrf_to_body, sub_point
    from .tables import in_frame

    seen = moon_seen_from(observer, when, t, source)
    mats = in_frame(icrf_to_body(solution.part("moon.q", t - seen["light_time_d"])), frame)
    lon, lat = sub_point(mats, -seen["apparent"])
    return {"sub_observer_longitude": lon, "sub_observer_latitude": lat,
            "axis_position_angle": axis_position_angle(when, seen["apparent"], mats[:, 2, :])}
