"""The astronomer's frames from the API: the CIO locator and the GCRS-to-CIRS matrix of the Earth's pole (against
ERFA's IAU 2006/2000A), the Moon's mean-Earth frame and an observer's libration (against CSPICE and skyfield
reading JPL's lunar PCK and frame kernel)."""
import numpy as np
import pytest
from astropy.time import Time

import spinorbit
from spinorbit.errors import InputError

from .units import arcsec, mas

uas = mas / 1000
DATES_2020S = Time(["2021-02-11", "2024-07-30T06:00", "2029-12-05T18:30"], scale="utc")


def rotation_angle(a, b):
    """Angle (rad) between rotation matrices (n, 3, 3), accurate for small angles."""
    return np.linalg.norm(a - b, axis=(1, 2)) / np.sqrt(2.0)


@pytest.mark.slow
def test_the_cio_locator_and_the_celestial_to_intermediate_matrix_are_iau_2006_2000as():
    """s within 1 uas of ERFA's s06a and the matrix within 1 mas of c2i06a: the model's CIP is within 0.6 mas of
    IAU 2006/2000A's over 1950-2050, and s moves with it by -(X dY + Y dX) / 2 (X ~ 0.002 rad in the 2020s)."""
    import erfa

    table = spinorbit.earth_pole(DATES_2020S)
    tt = DATES_2020S.tt
    s = table["cio_locator_s"].to_value("rad")
    assert np.max(np.abs(s - erfa.s06a(tt.jd1, tt.jd2))) < 1 * uas
    matrices = np.asarray(table["celestial_to_intermediate"])
    assert matrices.shape == (3, 3, 3)
    assert np.max(rotation_angle(matrices, erfa.c2i06a(tt.jd1, tt.jd2))) < 1 * mas


@pytest.mark.slow
def test_spinorbit_at_earth_writes_the_matrix_one_element_a_csv_column(capsys):
    """CSV holds one value a cell: the GCRS-to-CIRS matrix is nine columns, row by row, each ERFA c2i06a's within
    1 mas (the model's CIP's distance from IAU's)."""
    import csv
    import io

    import erfa

    from spinorbit.cli import main

    assert main(["--quiet", "at", "earth", "2024-07-30T06:00", "--scale", "tt"]) == 0
    row = next(csv.DictReader(io.StringIO(capsys.readouterr().out)))
    matrix = np.array([[float(row[f"celestial_to_intermediate_{i}{j}"]) for j in (1, 2, 3)] for i in (1, 2, 3)])
    tt = Time("2024-07-30T06:00", scale="tt")
    assert rotation_angle(matrix[None], erfa.c2i06a(tt.jd1, tt.jd2)[None])[0] < 1 * mas


def jpl_lunar_kernels():
    """JPL's moon_pa_de421_1900-2050.bpc and moon_080317.tf (shipped by lunarsky) and DE421's .bsp (skyfield-data)."""
    from spinorbit.orbits.kernel import kernel_path
    from spinorbit.references.moon_de421 import _pck_paths

    return [*_pck_paths(), str(kernel_path("de421"))]


def tdb_seconds(when):
    tdb = when.tdb
    return ((tdb.jd1 - 2451545.0) + tdb.jd2) * 86400.0


def sub_earth_by_cspice(spiceypy, frame, seconds):
    """(longitude, latitude) rad of the Earth's geometric direction from the Moon in ``frame`` (spkpos, no
    aberration correction), as CSPICE reads the kernels loaded."""
    lon, lat = np.transpose([spiceypy.reclat(spiceypy.spkpos("EARTH", et, frame, "NONE", "MOON")[0])[1:]
                             for et in seconds])
    return lon, lat


def point_angle(lon_a, lat_a, lon_b, lat_b):
    """Angle (rad) between two points on the sphere (rad), accurate for small angles."""
    a = np.stack([np.cos(lat_a) * np.cos(lon_a), np.cos(lat_a) * np.sin(lon_a), np.sin(lat_a)], axis=-1)
    b = np.stack([np.cos(lat_b) * np.cos(lon_b), np.cos(lat_b) * np.sin(lon_b), np.sin(lat_b)], axis=-1)
    return np.linalg.norm(a - b, axis=-1)


def test_the_mean_earth_sub_earth_point_is_cspices_on_jpls_pck_and_frame_kernel():
    """The ME sub-Earth point within 0.01" of CSPICE's in MOON_ME_DE421 (JPL's PCK and frame kernel, DE421's
    orbits): the Moon's orientation is within 2.5 mas (pole) and 0.5 mas (longitude) of DE421's over 1900-2050;
    the ME frame's 104" turn from the principal axes (a sign or an order wrong) would be seen 10^4 times over."""
    spiceypy = pytest.importorskip("spiceypy")
    table = spinorbit.moon_librations(DATES_2020S, frame="ME")
    assert table.meta["frame"]["name"] == "ME"
    lon, lat = (table[f"sub_earth_{c}"].to_value("rad") for c in ("longitude", "latitude"))
    try:
        for path in jpl_lunar_kernels():
            spiceypy.furnsh(path)
        jpl_lon, jpl_lat = sub_earth_by_cspice(spiceypy, "MOON_ME_DE421", tdb_seconds(DATES_2020S))
        pa_lon, pa_lat = sub_earth_by_cspice(spiceypy, "MOON_PA_DE421", tdb_seconds(DATES_2020S))
    finally:
        spiceypy.kclear()
    assert np.max(point_angle(lon, lat, jpl_lon, jpl_lat)) < 0.01 * arcsec
    assert np.min(point_angle(lon, lat, pa_lon, pa_lat)) > 50 * arcsec        # ME is not PA


def test_a_bad_frame_is_named():
    with pytest.raises(InputError, match="frame: got 'me'; expected one of \\['PA', 'ME'\\]"):
        spinorbit.moon_librations(DATES_2020S, frame="me")


def test_the_exported_moon_carries_the_mean_earth_frame_as_jpls(tmp_path, monkeypatch):
    """The exported frame kernel's MOON_ME_SPINORBIT_<id> is turned from its PA frame as JPL's MOON_ME_DE421 from
    MOON_PA_DE421 (CSPICE reading both frame kernels: to rounding), and CSPICE's sub-Earth point in it is the
    API's ME answer within 1 uas (the PCK's refit, 6e-8")."""
    spiceypy = pytest.importorskip("spiceypy")
    from spinorbit import solutions
    from spinorbit.solutions import store

    monkeypatch.setitem(store.PLACE, "directory", tmp_path / "store")
    (tmp_path / "store").mkdir()
    written = solutions.solve("moon_libration", [], -10.0, 30.0).export(tmp_path / "out")
    when = Time(2451545.0, [-5.25, 3.5, 21.75], format="jd", scale="tdb")
    table = spinorbit.moon_librations(when, frame="ME")
    lon, lat = (table[f"sub_earth_{c}"].to_value("rad") for c in ("longitude", "latitude"))
    try:
        for path in [*written["files"], *jpl_lunar_kernels()]:
            spiceypy.furnsh(path)
        principal = written["frames"]["moon"]
        mean_earth = written["frames"]["moon_mean_earth"]
        ours = np.array(spiceypy.pxform(principal, mean_earth, 0.0))
        jpls = np.array(spiceypy.pxform("MOON_PA_DE421", "MOON_ME_DE421", 0.0))
        read_lon, read_lat = sub_earth_by_cspice(spiceypy, mean_earth, tdb_seconds(when))
    finally:
        spiceypy.kclear()
    assert np.max(np.abs(ours - jpls)) < 1e-15
    assert np.max(point_angle(lon, lat, read_lon, read_lat)) < 1 * uas


PLACE = {"lon_deg": -17.8792, "lat_deg": 28.7606, "height_m": 2396.0}          # La Palma, Roque de los Muchachos
DATES_OBSERVED = Time(["2021-02-11T20:00", "2023-05-03T03:10", "2024-07-30T06:00"], scale="utc")


def observed_by_skyfield(when, frame_name):
    """(sub-observer longitude, latitude, the axis's position angle) rad from PLACE by skyfield's own chain: its
    timescale's UT1 and the polar motion of skyfield-data's finals2000A.all, its observe().apparent() on DE421,
    JPL's lunar PCK and frame kernel at the light's departure, its true equator of date (Time.M) and its
    position_angle_of."""
    from skyfield.api import load, wgs84
    from skyfield.data import iers
    from skyfield.planetarylib import PlanetaryConstants
    from skyfield.trigonometry import position_angle_of
    from skyfield.units import Angle
    from skyfield_data import get_skyfield_data_path

    fk, bpc, bsp = jpl_lunar_kernels()
    ts = load.timescale()
    with load.open(f"{get_skyfield_data_path()}/finals2000A.all") as finals:
        iers.install_polar_motion_table(ts, iers.parse_x_y_dut1_from_finals_all(finals))
    constants = PlanetaryConstants()
    constants.read_text(load.open(fk))
    constants.read_binary(load.open(bpc))
    frame = constants.build_frame_named(frame_name)
    planets = load(bsp)
    t = ts.from_astropy(when)
    seen = (planets["earth"] + wgs84.latlon(PLACE["lat_deg"], PLACE["lon_deg"], PLACE["height_m"])).at(t) \
        .observe(planets["moon"]).apparent()
    rotation = frame.rotation_at(ts.tdb_jd(t.tdb - seen.light_time))                 # (3, 3, n)
    u = np.einsum("ijn,jn->ni", rotation, -seen.position.au)
    lon, lat = np.arctan2(u[:, 1], u[:, 0]), np.arcsin(u[:, 2] / np.linalg.norm(u, axis=1))
    apparent = np.einsum("ijn,jn->in", t.M, seen.position.au)
    pointer = apparent / np.linalg.norm(apparent, axis=0) + 1e-3 * np.einsum("ijn,jn->in", t.M, rotation[2])

    def pair(v):
        return (Angle(radians=np.arcsin(v[2] / np.linalg.norm(v, axis=0))),
                Angle(radians=np.arctan2(v[1], v[0]), preference="hours"))      # a right ascension: east positive

    return lon, lat, position_angle_of(pair(apparent), pair(pointer)).radians


@pytest.mark.parametrize("frame", ["PA", "ME"])
def test_an_observers_libration_is_skyfields_on_jpls_pck(frame):
    """The sub-observer point within 0.02" and the axis's position angle within 0.02" of skyfield's at La Palma:
    the Moon's orientation is within 2.5 mas of DE421's; astropy's and skyfield's Earth rotation place the
    observer within ~10 m (5 mas at the Moon).  The observer's parallax (~1 deg) and the light time (the Moon
    turns 0.7" in 1.3 s) are each far above the tolerance."""
    import astropy.units as u
    from astropy.coordinates import EarthLocation

    pytest.importorskip("skyfield_data")
    place = EarthLocation.from_geodetic(PLACE["lon_deg"] * u.deg, PLACE["lat_deg"] * u.deg, PLACE["height_m"] * u.m)
    table = spinorbit.moon_librations(DATES_OBSERVED, frame=frame, observer=place)
    lon, lat = (table[f"sub_observer_{c}"].to_value("rad") for c in ("longitude", "latitude"))
    sky_lon, sky_lat, sky_angle = observed_by_skyfield(DATES_OBSERVED, f"MOON_{frame}_DE421")
    assert np.max(point_angle(lon, lat, sky_lon, sky_lat)) < 0.02 * arcsec
    difference = (table["axis_position_angle"].to_value("rad") - sky_angle + np.pi) % (2 * np.pi) - np.pi
    assert np.max(np.abs(difference)) < 0.02 * arcsec
    earth = (table[f"sub_earth_{c}"].to_value("rad") for c in ("longitude", "latitude"))
    assert np.min(point_angle(lon, lat, *earth)) > 0.1 * np.pi / 180        # the place is not the Earth's centre


def test_an_observer_is_one_earth_location_and_its_dates_within_the_iers_tables():
    import astropy.units as u
    from astropy.coordinates import EarthLocation

    with pytest.raises(InputError, match="^observer: got 'La Palma'; expected one astropy EarthLocation"):
        spinorbit.moon_librations(DATES_OBSERVED, observer="La Palma")
    place = EarthLocation.from_geodetic(PLACE["lon_deg"] * u.deg, PLACE["lat_deg"] * u.deg, PLACE["height_m"] * u.m)
    with pytest.raises(InputError, match="^times: .*1960-01-01.*expected dates whose UT1 astropy's IERS tables hold"):
        spinorbit.moon_librations(Time(["1960-01-01", "2021-02-11"], scale="utc"), observer=place)
    with pytest.raises(InputError, match="^observer: got \"ephemeris='rebound'\"; expected an ephemeris that is"):
        spinorbit.moon_librations(DATES_OBSERVED, observer=place, ephemeris="rebound")
