"""A solar-system run against DE421: the Moon (direction, range), the lunar pole and longitude, every planet's
heliocentric position; and the share of what is left that DE421's asteroids, absent here, account for.

Edge module (astropy units); the scene declares, this compares.
"""
import numpy as np

from ..analysis.librations import LONGITUDE_ERROR_MAX_ARCSEC, POLE_ERROR_MAX_ARCSEC
from ..base.constants import MAS
from ..models.assemblies.solar_system import PLANETS
from .earth_moon_de421 import lunar_errors, orbit_errors

HELIOCENTRIC = (*PLANETS[:2], "earth", *PLANETS[2:])
# The metrics ``metrics`` computes (the summary's comparison keys, read by the verdict)
MOON_DIRECTION_ERROR_MAX_MAS, MOON_DIRECTION_ERROR_RMS_MAS = ("moon_direction_error_max_mas",
                                                              "moon_direction_error_rms_mas")
MOON_RANGE_ERROR_MAX_M, MOON_RANGE_ERROR_RMS_M = "moon_range_error_max_m", "moon_range_error_rms_m"
POLE_ERROR_MAX_MAS, LONGITUDE_ERROR_MAX_MAS = "pole_error_max_mas", "longitude_error_max_mas"


def heliocentric_error_max_km(body):
    """The metric of ``body``'s largest heliocentric position error, km."""
    return f"{body}_heliocentric_error_max_km"

# What DE421's asteroids move in each planet, km over 1950-2050, measured (benchmarks/asteroid_share.py):
# Ceres, Pallas and Vesta added with DE421's masses (MA0001, MA0002, MA0004) from DE430's states at JDEPOC
# (Folkner et al. 2014); the difference of the runs with and without them times 1.35, the header's 67 known
# masses over theirs.
ASTEROIDS_KM = {"mercury": 0.72, "venus": 0.75, "earth": 2.2, "mars": 69.0, "jupiter": 54.0, "saturn": 52.0,
                "uranus": 15.0, "neptune": 39.0, "pluto": 35.0}
ASTEROIDS_MOON = {"direction_mas": 2.3, "range_m": 0.54}        # the same, the geocentric Moon


def heliocentric(system, solution):
    """{body: (n, 3) heliocentric positions, km} of the planets and the Earth in a barycentric run."""
    sun = solution.part("sun.r")
    out = {name: solution.part(f"{name}.r") - sun for name in PLANETS}
    moon = system.motion.share * solution.part("moon.r")
    out["earth"] = solution.part("earth_moon_barycenter.r") - moon - sun
    return {name: out[name] for name in HELIOCENTRIC}


def planet_errors(t, positions):
    """{body: |x - x_DE421| (n,), km} of heliocentric positions {body: (n, 3)} at TDB days t."""
    from ..orbits.kernel import open_ephemeris

    ephemeris = open_ephemeris("de421", float(np.min(t)), float(np.max(t)))
    return {name: np.linalg.norm(x - ephemeris.relative_states(name, "sun", t)[0], axis=1)
            for name, x in positions.items()}


def metrics(direction, distance, lunar, planets):
    """The summary's comparison: the Moon in mas and m, the lunar angles in mas, each planet's max in km."""
    out = {MOON_DIRECTION_ERROR_MAX_MAS: float(direction.max() / MAS),
           MOON_DIRECTION_ERROR_RMS_MAS: float(np.sqrt(np.mean(direction ** 2)) / MAS),
           MOON_RANGE_ERROR_MAX_M: float(np.abs(distance).max() * 1e3),
           MOON_RANGE_ERROR_RMS_M: float(np.sqrt(np.mean(distance ** 2)) * 1e3),
           POLE_ERROR_MAX_MAS: float(lunar[POLE_ERROR_MAX_ARCSEC] * 1e3),
           LONGITUDE_ERROR_MAX_MAS: float(lunar[LONGITUDE_ERROR_MAX_ARCSEC] * 1e3)}
    for name, error in planets.items():
        out[heliocentric_error_max_km(name)] = float(error.max())
    return out


def table(t, r, mats, errors, planets):
    """The run's table: the geocentric Moon (km, ICRF) and its errors, the Moon's JPL 3-1-3 angles (rad, from
    its ICRF-to-body matrices ``mats``) and the lunar pole and longitude errors, each planet's heliocentric
    error.  errors: {name: array} in rad and km."""
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
    out["moon_direction_error"] = errors["direction"] / MAS * u.mas
    out["moon_range_error"] = errors["range"] * 1e3 * u.m
    out["pole_error"] = errors["pole"] / MAS * u.mas
    out["longitude_error"] = errors["longitude"] / MAS * u.mas
    for name, error in planets.items():
        out[f"{name}_heliocentric_error"] = error * u.km
    return out


def lunar(t, q):
    """(ICRF-to-body matrices, pole and longitude differences (rad), their metrics) of the Moon's attitudes
    q (n, 4) vs DE421."""
    mats, _, pole, longitude, metrics_ = lunar_errors(t, q)
    return mats, pole, longitude, metrics_


__all__ = ["HELIOCENTRIC", "heliocentric", "lunar", "metrics", "orbit_errors", "planet_errors", "table"]
