"""The API's dates as hostile input: a masked Time is refused in one line (there is no date to answer for), a
2-D Time gives one row per date (row by row), dates a scene's span cannot name (before 1000, after 9999) and an
N-body run the estimate puts over the API's limit are refused on ``times`` with the dates the caller gave.

The references: the same dates given flat (a 2-D Time must answer each as the 1-D one does, to the bit), and the
count of days REBOUND integrates (DE421's nearest date to the dates: a closed form) times the measured cost."""
import numpy as np
import pytest
from astropy.time import Time

import spinorbit
from spinorbit import api
from spinorbit.errors import InputError


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
    from spinorbit.scene import NBODY_COSTS

    t = Time("5000-01-01", scale="tdb")
    days = (t.jd - 2451545.0) + 4.0             # the Moon's solution runs from J2000 - 2 d to the date + 2 d
    minutes = days * NBODY_COSTS["IAS15 days"] / 60
    assert minutes > api.API_TIME_LIMIT_S / 60                     # the case asks for more than the limit
    with pytest.raises(InputError, match="N-body run the estimate finishes within 10 min") as info:
        spinorbit.moon_librations(t, ephemeris="rebound")
    text = str(info.value)
    assert text.startswith("times: got '5000-01-01'") and f"integrates {days:.3g} days" in text
    assert f"~{minutes:.3g} min" in text and "\n" not in text
