"""The Earth model's pieces that do not depend on the choice of H_d: the planets it may add, the pole its
geodesic precession turns about, a start on a pole, and the rigid nutation REN-2000 gives (with the model's
geodesic nutation) -- what the start (earth.py), the observed-rate H_d (earth_ellipticity.py) and
the non-rigid layer (comparisons/earth_nonrigid.py) share."""
import math

import numpy as np

from ..base.constants import ARCSEC, JULIAN_CENTURY_D
from ..bodies import earth
from ..references import ren2000

PLANETS = ("mercury", "venus", "mars", "jupiter", "saturn")


def ecliptic_pole(tilt):
    """The pole the geodesic precession turns about: the J2000 ecliptic's, or that of Euler's tilted
    circles."""
    from ..references import erfa_pole

    return (erfa_pole.ecliptic_pole_j2000() if tilt is None
            else np.array([0.0, -math.sin(tilt), math.cos(tilt)]))


def started(system, t0, pole, forced=True):
    """``system`` with the Earth's figure axis at ``pole`` at t0 spinning at the Earth rotation angle's rate
    (its body x axis toward the A axis, longitude -14.93 deg, for a triaxial Earth)."""
    from ..models.start import on_pole

    state = on_pole(system, "earth", t0, pole, earth.ERA_RATE_RAD_D, a_axis(t0, pole), forced)
    system.y0 = system.layout.pack(state)
    return system


def a_axis(t0, z0):
    """Direction of the body x axis at t0: the A axis (longitude -14.93 deg) for a triaxial Earth."""
    from ..references import erfa_pole

    x_tirs = erfa_pole.terrestrial_x_axis(t0)
    lon = math.radians(earth.A_AXIS_LONGITUDE_DEG)
    return math.cos(lon) * x_tirs + math.sin(lon) * np.cross(z0, x_tirs)


def geodesic_nutation(t_tdb_d):
    """The model's geodesic nutation in longitude (rad) at TDB days: the annual term of its geodesic
    precession (models.interactions.geodesic.GeodesicRate: Omega_gp (1 + 3 e cos l')) integrated,
    -(3 e Omega_gp / n') sin l' (Fukushima 1991)."""
    rate = earth.GEODESIC_PRECESSION_ARCSEC_CY * ARCSEC / JULIAN_CENTURY_D
    from ..models.assemblies.earth import ORBIT_ECCENTRICITY, SUN_MEAN_ANOMALY_RAD

    l0, n = SUN_MEAN_ANOMALY_RAD
    return -3.0 * ORBIT_ECCENTRICITY * rate / n * np.sin(l0 + n * np.asarray(t_tdb_d))


def ren2000_scaled(t, h_d, geodesic):
    """REN-2000's (dpsi, deps), rad, on its tabulated constituents, times h_d / H_REN (a rigid Earth's
    first-order nutation goes as H), plus the model's geodesic nutation if ``geodesic`` (REN-2000 has
    none)."""
    dpsi, deps = ren2000.nutation(t)
    return dpsi * h_d / ren2000.H + (geodesic_nutation(t) if geodesic else 0.0), deps * h_d / ren2000.H
