"""earth_deep_time's table: La2004's quantities (and the orbit's elements, the Moon's distance, the length of
day) at the output times, with units."""
import numpy as np

from ..scene.columns import quantity_table
from ..starts.earth_deep_time import KYR_D


def quantities(t, states, model):
    """La2004's quantities and the rest of the table at times t from the spin states and the orbit."""
    import erfa

    from ..bodies import moon
    from ..models import deep_time
    from ..orbits.solution import elements

    normal, eccentricity_vector = model.system.orbit(t)
    angles = deep_time.climate_angles(states[:, :3], normal, eccentricity_vector, model.spin_axis0,
                                      model.normal0)
    e, varpi, inclination, node = elements(normal, eccentricity_vector, erfa.ecm06(2451545.0, 0.0))
    return {"t_kyr": t / KYR_D, "eccentricity": e, **angles,
            "climatic_precession": e * np.sin(angles["perihelion_longitude"]),
            "perihelion_longitude_j2000": varpi, "inclination": inclination, "node": node,
            "lunar_distance": states[:, 3] * moon.MEAN_DISTANCE_KM, "length_of_day": 24.0 / states[:, 4]}


COLUMNS = {  # name: (unit, description)
    "t_kyr": ("kyr", "time from J2000 (TDB), as La2004"),
    "eccentricity": ("", "the Earth-Moon barycentre's heliocentric osculating eccentricity"),
    "obliquity": ("rad", "angle between the spin axis and the orbit's normal"),
    "perihelion_longitude": ("rad", "varpi_bar: longitude of perihelion from the moving equinox"),
    "climatic_precession": ("", "e sin(varpi_bar)"),
    "precession": ("rad", "psi: general precession in longitude from J2000 (varpi_bar = varpi + psi)"),
    "perihelion_longitude_j2000": ("rad", "varpi: longitude of perihelion from the J2000 equinox, ecliptic"),
    "inclination": ("rad", "the orbit's inclination to the J2000 ecliptic (IAU 2006)"),
    "node": ("rad", "the orbit's ascending node on the J2000 ecliptic, from the J2000 equinox"),
    "lunar_distance": ("km", "the Moon's mean distance under tidal dissipation"),
    "length_of_day": ("h", "length of day under tidal dissipation (24 h today)"),
}


def table(t, q):
    return quantity_table(t, q, COLUMNS)
