"""A lunar run against DE421: the output table of angles, residuals and librations, and the error of the
integration against run time (a converged run and DE421 as the references).

Edge module (astropy units); the Moon scene declares, this compares.
"""
import numpy as np

from ..analysis.librations import (
    LONGITUDE_ERROR_MAX_ARCSEC,
    LONGITUDE_ERROR_RMS_ARCSEC,
    POLE_ERROR_MAX_ARCSEC,
    POLE_ERROR_RMS_ARCSEC,
)
from ..base.constants import ARCSEC

LADDER = ([("rk8", {"step": h}) for h in (4.0, 2.0, 1.0, 0.5)]          # report.error_vs_runtime
          + [("dop853", {"rtol": r, "atol": r * 1e-2}) for r in (1e-8, 1e-10, 1e-12)])
CONVERGED = ("rk8", {"step": 0.25})
# What a run driven by another source can reach (the verdict's note; measured in benchmarks/RESULTS.md).
SOURCE_NOTES = {"rebound": (
    "orbits from rebound: expect no better than REBOUND's lunar orbit, which lacks the figures and tides and "
    "drifts from DE421's (the Moon's direction 0.3\" in 1 yr, 3\" in 10 yr, 23\" and 41 km over 1969-2019; "
    "the longitude follows it: 19.8\"); for DE421's accuracy from REBOUND's bodies run "
    "scenarios/earth_moon_coupled_rebound.toml (the Moon integrated with the coupled forces: "
    "longitude 0.019\", pole 0.0034\" over 1969-2019)")}


def against_de421(t, mats):
    """(DE421's orientation on the outputs its series covers (a Comparable, or None), the covered rows (mask),
    the comparison's metrics, {metric: why not measured}): outside DE421's span nothing is compared."""
    from ..analysis.librations import residual_metrics
    from ..base.errors import tdb_dates
    from ..bodies.de421_orientation import span

    de421, covered = de421_where_covered(t)
    if de421 is None:
        why = f"DE421's lunar orientation covers {tdb_dates(span())} TDB; this span lies outside it"
        return None, covered, {}, {f"comparison.{k}": why for k in METRICS}
    return de421, covered, residual_metrics(mats[covered], de421["icrf_to_body"]), {}


def de421_where_covered(t):
    """(DE421's orientation at the dates ``t`` its series covers (a Comparable, or None if it covers none), the
    covered rows (mask))."""
    from ..bodies.de421_orientation import span
    from ..references.moon_de421 import Orientation

    first, last = span()
    covered = (t >= first) & (t <= last)
    return (Orientation()(t[covered]) if covered.any() else None), covered


METRICS = (POLE_ERROR_MAX_ARCSEC, POLE_ERROR_RMS_ARCSEC, LONGITUDE_ERROR_MAX_ARCSEC, LONGITUDE_ERROR_RMS_ARCSEC)


def table(solution, mats, de421, covered, lib):
    """The attitude, the JPL angles and their residuals against DE421 (NaN where it has no data), the physical
    librations and the sub-Earth point."""
    import astropy.units as u

    from ..analysis.librations import pole_and_longitude_difference
    from ..base.rotations import euler313_from_matrix
    from ..scene.run_result import attitude_table

    table, angles = attitude_table(solution), euler313_from_matrix(mats)
    arcsec = lambda x: x / ARCSEC * u.arcsec
    residuals = np.full((len(angles), 5), np.nan)             # pole, longitude, phi, theta, psi
    if de421 is not None:
        difference = pole_and_longitude_difference(mats[covered], de421["icrf_to_body"])
        residuals[covered, :2] = np.transpose(difference)
        residuals[covered, 2:] = (angles[covered] - de421["angles_rad"] + np.pi) % (2 * np.pi) - np.pi
    for i, name in enumerate(("phi", "theta", "psi")):
        table[name] = angles[:, i] * u.rad
    table["pole_error"], table["longitude_error"] = arcsec(residuals[:, 0]), arcsec(residuals[:, 1])
    for i, name in enumerate(("phi", "theta", "psi")):
        table[f"{name}_minus_de421"] = arcsec(residuals[:, 2 + i])
    for name, key in (("longitude", "tau"), ("latitude", "rho"), ("node", "sigma")):
        table[f"libration_{name}"] = arcsec(lib[key])
    table["sub_earth_longitude"] = np.degrees(lib["sub_earth_lon"]) * u.deg
    table["sub_earth_latitude"] = np.degrees(lib["sub_earth_lat"]) * u.deg
    return table


def error_vs_runtime(system, t_out, de421_mats):
    """LADDER's wall time and max attitude error vs a converged rk8 run and vs DE421, arcsec."""
    from ..analysis.ladder import work_precision
    from ..analysis.librations import attitude_error, icrf_to_body
    from ..integrators import simulate

    converged = icrf_to_body(simulate(system, t_out, *CONVERGED, estimate_error=False)[0].quaternion)
    errors = {"error_vs_converged_arcsec": attitude_error(converged),
              "error_vs_de421_arcsec": attitude_error(de421_mats)}
    return work_precision(system, t_out, LADDER, lambda sol: {k: f(sol) / ARCSEC for k, f in errors.items()})


def beside_de421(terms, de421_terms):
    """Put DE421's own fitted coefficient (``de421_arcsec``) beside each term's fit: where the model and
    DE421 agree and Eckhardt's published series (1981, fitted to older data) differs, the difference is
    Eckhardt's."""
    for part in ("main", "other"):
        for row, other in zip(terms[part], de421_terms[part]):
            row["de421_arcsec"] = other["fitted_arcsec"]
    terms["note"] = ("fitted_arcsec: the model's tau fitted on Eckhardt's arguments; de421_arcsec: DE421's "
                     "own tau fitted alike; where the two agree and published_arcsec (Eckhardt 1981, "
                     "Meeus ch. 53) differs, e.g. the 18.6-yr term's 0.8\", the difference is the older "
                     "series', not the integration's")


def longitude_terms(t, mats, earth, de421, covered):
    """(the run's physical librations (references.eckhardt, ``earth`` the Earth seen from the Moon), the
    longitude terms fitted to them, with DE421's own fitted alike beside where it covers (where Eckhardt's series
    differs), {term: why refused})."""
    from ..references import eckhardt
    from ..references.moon_de421 import FREE_LIBRATION_LONGITUDE_PERIOD_D

    lib = eckhardt.physical_librations(t, mats, earth)
    terms, refused = eckhardt.fit_longitude_terms(t, lib["tau"] / ARCSEC, FREE_LIBRATION_LONGITUDE_PERIOD_D)
    if de421 is not None:
        beside_de421(terms, eckhardt.fit_longitude_terms(t[covered], eckhardt.physical_librations(
            t[covered], de421["icrf_to_body"], earth[covered])["tau"] / ARCSEC,
            FREE_LIBRATION_LONGITUDE_PERIOD_D)[0])
    return lib, terms, refused


ZOOM_D = 730.5                      # the figure's last two years against DE421, days


def last_years(t, covered, de421, earth):
    """(the outputs of the last ZOOM_D days DE421 covers, DE421's physical librations there), or (None, None)
    where it covers none."""
    from ..references import eckhardt

    zoom = covered & (np.abs(t - t[covered][-1]) <= ZOOM_D) if covered.any() else None
    de421_zoom = None if zoom is None else eckhardt.physical_librations(
        t[zoom], de421["icrf_to_body"][zoom[covered]], earth[zoom])
    return zoom, de421_zoom


def model_summary(level, system, orbits):
    """The summary's model section: the lunar level, its degree, core, tides, bodies and terms."""
    from ..models.assemblies.moon import LEVELS

    return {"level": level, "name": LEVELS[level].name, "start_tdb_d": system.t0,
            "degree": 4 if "harmonics" in system.meta["terms"] else 2,
            "core": LEVELS[level].core, "tides": bool(system.meta["tides"]),
            "bodies": list(orbits.names), "terms": list(system.meta["terms"])}


def orbit_summary(source, step_d, orbits):
    """The orbit source as the summary reports it (the interpolant's measured error where it has one)."""
    error = getattr(orbits, "max_error_km", None)
    return {"source": source, "step_d": step_d,
            "max_error_km": None if error is None else [float(v) for v in np.atleast_1d(error)]}


def driven_by_metrics(other, pole, lon):
    """Max pole and longitude differences (arcsec) from the same run driven by orbit source ``other``."""
    return {f"pole_difference_vs_{other}_driven_max_arcsec": float(np.abs(pole).max() / ARCSEC),
            f"longitude_difference_vs_{other}_driven_max_arcsec": float(np.abs(lon).max() / ARCSEC)}
