"""The API's frames against independent references, over many dates.

    python benchmarks/bench_frames.py [cio|me|observer|all] [--dates N]

* cio: ``earth_pole``'s CIO locator s and GCRS-to-CIRS matrix at N dates over 1950-2050 (the validated non-rigid
  Earth's century), against ERFA's IAU 2006/2000A (``s06a``, ``c2i06a``): the largest difference, and where s
  differs by more than 1 uas, what the model's CIP makes of it (-(X dY + Y dX) / 2).
* me: ``moon_librations(frame="ME")``'s sub-Earth point at N dates over 1900-2050 (JPL's lunar PCK's span),
  against CSPICE on JPL's ``moon_pa_de421_1900-2050.bpc`` and ``moon_080317.tf`` (frame MOON_ME_DE421, DE421's
  orbits), against DE421's own librations (the ``de421`` package's arrays) turned by CSPICE's PA-to-ME matrix,
  and against CSPICE reading the Moon's kernels ``export`` writes (frame MOON_ME_SPINORBIT_<id>).
* observer: ``moon_librations(observer=...)`` at La Palma, N dates over 1973-2025 (where the IERS tables astropy
  and skyfield-data ship hold measured UT1 and polar motion), in both frames, against skyfield's own chain
  (tests/edge/test_api.observed_by_skyfield: its UT1, skyfield-data's polar motion, ``observe().apparent()``
  on DE421, JPL's lunar PCK and frame kernel): the sub-observer point and the axis's position angle, and how far
  astropy and skyfield place the observer (m); the call's time for the N dates without and with the observer.
"""
import argparse
import json
import time
import warnings

import numpy as np

UAS = np.pi / 180 / 3600 / 1e6
MAS = UAS * 1e3
CENTURY_1950_2050 = (-18262.5 + 1.0, 18262.5 - 1.0)         # TDB days from J2000


def dates(span, count, seed):
    from astropy.time import Time

    days = np.sort(np.random.default_rng(seed).uniform(*span, count))
    return Time(2451545.0, days, format="jd", scale="tdb")


def rotation_angle(a, b):
    return np.linalg.norm(a - b, axis=(1, 2)) / np.sqrt(2.0)


def cio(count):
    import erfa

    import spinorbit

    t = dates(CENTURY_1950_2050, count, 44)
    table = spinorbit.earth_pole(t)
    tt = t.tt
    s = table["cio_locator_s"].to_value("rad")
    ds = s - erfa.s06a(tt.jd1, tt.jd2)
    x, y = table["cip_x"].to_value("rad"), table["cip_y"].to_value("rad")
    dx, dy = table["cip_x_minus_erfa"].to_value("rad"), table["cip_y_minus_erfa"].to_value("rad")
    by_cip = -(x * dy + y * dx + dx * dy) / 2                     # s06's -XY/2 of the model's CIP less IAU's
    over = np.abs(ds) > UAS
    years = 2000.0 + (t.tdb.jd1 - 2451545.0 + t.tdb.jd2) / 365.25
    angle = rotation_angle(np.asarray(table["celestial_to_intermediate"]), erfa.c2i06a(tt.jd1, tt.jd2))
    return {"dates": count, "span": "1950-2050", "s_minus_s06a_max_uas": float(np.abs(ds).max() / UAS),
            "dates_over_1_uas": int(over.sum()),
            "years_over_1_uas": [round(float(y), 2) for y in years[over]],
            "s_minus_s06a_less_the_cip_term_max_uas": float(np.abs(ds - by_cip).max() / UAS),
            "matrix_minus_c2i06a_max_mas": float(angle.max() / MAS)}


JPL_PCK_1900_2050 = (-36524.5 + 1.0, 18262.5 - 1.0)       # TDB days: moon_pa_de421_1900-2050.bpc


def unit(lon, lat):
    return np.stack([np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon), np.sin(lat)], axis=-1)


def cspice_sub_earth(spiceypy, frame, seconds):
    """The Earth's geometric direction from the Moon (unit vectors) in ``frame``, as CSPICE reads the kernels."""
    r = np.array([spiceypy.spkpos("EARTH", et, frame, "NONE", "MOON")[0] for et in seconds])
    return r / np.linalg.norm(r, axis=1, keepdims=True)


def me(count):
    import tempfile

    import spiceypy

    import spinorbit
    from spinorbit import solutions
    from spinorbit.base.rotations import matrix_from_euler313
    from spinorbit.edge.scenarios import load_scenario
    from spinorbit.orbits.kernel import kernel_path
    from spinorbit.references.moon_de421 import _pck_paths, librations

    t = dates(JPL_PCK_1900_2050, count, 45)
    days = t.tdb.jd1 - 2451545.0 + t.tdb.jd2
    seconds = days * 86400.0
    table = spinorbit.moon_librations(t, frame="ME")
    ours = unit(table["sub_earth_longitude"].to_value("rad"), table["sub_earth_latitude"].to_value("rad"))
    out = {"dates": count, "span": "1900-2050"}
    with tempfile.TemporaryDirectory() as folder:
        solution = solutions.for_scenario(load_scenario("moon_libration"), days.min() - 1.0, days.max() + 1.0)
        written = solution.export(folder)
        try:
            for path in [*_pck_paths(), str(kernel_path("de421")), *written["files"]]:
                spiceypy.furnsh(path)
            jpl = cspice_sub_earth(spiceypy, "MOON_ME_DE421", seconds)
            exported = cspice_sub_earth(spiceypy, written["frames"]["moon_mean_earth"], seconds)
            pa_to_me = np.array(spiceypy.pxform("MOON_PA_DE421", "MOON_ME_DE421", 0.0))
            earth_icrf = np.array([spiceypy.spkpos("EARTH", et, "J2000", "NONE", "MOON")[0] for et in seconds])
        finally:
            spiceypy.kclear()
    angles, _ = librations(days)
    arrays = np.einsum("ij,njk,nk->ni", pa_to_me, matrix_from_euler313(*angles.T), earth_icrf)
    arrays /= np.linalg.norm(arrays, axis=1, keepdims=True)
    for name, reference, scale, unit_name in (("cspice_jpl_pck_and_fk", jpl, MAS, "mas"),
                                              ("de421_arrays_turned_by_cspice", arrays, MAS, "mas"),
                                              ("cspice_our_export", exported, UAS, "uas")):
        difference = np.linalg.norm(ours - reference, axis=1) / scale
        out[f"vs_{name}_max_{unit_name}"] = float(difference.max())
        out[f"vs_{name}_rms_{unit_name}"] = float(np.sqrt(np.mean(difference ** 2)))
    return out


IERS_1973_2025 = (-9861.5, 9131.5)                          # TDB days: 1973-01-02 to 2025-01-01


def observer(count):
    import sys

    import astropy.units as u
    from astropy.coordinates import EarthLocation

    import spinorbit

    sys.path.insert(0, str(__import__("pathlib").Path(__file__).resolve().parents[1]))
    from tests.edge.test_api import PLACE, observed_by_skyfield

    t = dates(IERS_1973_2025, count, 46).utc
    place = EarthLocation.from_geodetic(PLACE["lon_deg"] * u.deg, PLACE["lat_deg"] * u.deg, PLACE["height_m"] * u.m)
    out = {"dates": count, "span": "1973-2025", "place": PLACE}
    for frame in ("PA", "ME"):
        table = spinorbit.moon_librations(t, frame=frame, observer=place)
        ours = unit(table["sub_observer_longitude"].to_value("rad"), table["sub_observer_latitude"].to_value("rad"))
        lon, lat, angle = observed_by_skyfield(t, f"MOON_{frame}_DE421")
        point = np.linalg.norm(ours - unit(lon, lat), axis=1) / MAS
        turn = np.abs((table["axis_position_angle"].to_value("rad") - angle + np.pi) % (2 * np.pi) - np.pi) / MAS
        out[frame] = {"sub_observer_max_mas": float(point.max()), "sub_observer_rms_mas": float(np.sqrt(np.mean(
            point ** 2))), "axis_position_angle_max_mas": float(turn.max())}
    out["observer_astropy_minus_skyfield_max_m"] = observer_apart(t, place)
    out["call_s"] = {}
    for label, options in (("without observer", {}), ("with observer", {"observer": place})):
        started = time.perf_counter()
        spinorbit.moon_librations(t, **options)
        out["call_s"][label] = time.perf_counter() - started
    return out


def observer_apart(t, place):
    """How far astropy (get_gcrs_posvel, its IERS table) and skyfield (its UT1, skyfield-data's polar motion)
    place the observer in the GCRS, m, at the largest."""
    import astropy.units as u
    from skyfield.api import load, wgs84
    from skyfield.data import iers
    from skyfield_data import get_skyfield_data_path

    ts = load.timescale()
    with load.open(f"{get_skyfield_data_path()}/finals2000A.all") as finals:
        iers.install_polar_motion_table(ts, iers.parse_x_y_dut1_from_finals_all(finals))
    lon, lat, height = place.to_geodetic()
    theirs = wgs84.latlon(lat.deg, lon.deg, height.to_value(u.m)).at(ts.from_astropy(t)).position.m
    ours = place.get_gcrs_posvel(t)[0].xyz.to_value(u.m)
    return float(np.linalg.norm(ours - theirs, axis=0).max())


PARTS = {"cio": cio, "me": me, "observer": observer}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("part", choices=[*PARTS, "all"], nargs="?", default="all")
    parser.add_argument("--dates", type=int, default=1000)
    args = parser.parse_args()
    warnings.simplefilter("ignore")          # ERFA's "dubious year" for UTC of future dates
    for name in PARTS if args.part == "all" else [args.part]:
        print(name, json.dumps(PARTS[name](args.dates), indent=1))


if __name__ == "__main__":
    main()
