"""earth_moon_history's table: the history at the output times, with units."""
from ..scene.columns import quantity_table

COLUMNS = {  # name: (unit, description)
    "t_gyr": ("Gyr", "time from J2000 (TDB), negative in the past"),
    "semi_major_axis": ("km", "the Moon's semi-major axis"),
    "eccentricity": ("", "the Moon's eccentricity"),
    "length_of_day": ("h", "the mean solar day, 2 pi / (Omega - n_sun)"),
    "obliquity": ("deg", "the angle between the Earth's spin axis and the ecliptic's normal"),
    "lunar_inclination": ("deg", "the Moon's orbit to the ecliptic"),
    "precession_constant": ("arcsec/yr", "p = alpha cos(eps), La2004's 50.475838\"/yr today"),
    "obliquity_period": ("kyr", "2 pi / (p + s3), s3 = -18.85\"/yr (today's)"),
    "precession_period": ("kyr", "2 pi / (p + g5), g5 = 4.257\"/yr (today's)"),
    "angular_momentum_error": ("", "(L_z - L_z today) / L_z today, the solar share included"),
}


def table(t, q):
    return quantity_table(t, q, COLUMNS)
