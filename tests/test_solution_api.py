"""The API answering from stored solutions: the Earth-Moon system at dates near its J2000 start, against DE421
at the coupled scene's tolerances; a second question inside the stored span integrates nothing."""
import numpy as np
import pytest
from astropy.time import Time

import spinorbit
from spinorbit.solutions import store

from .units import arcsec


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
