"""Dates and durations as a scenario key holds them (spinorbit.scene.schema): an ISO date in TDB or a duration from
span.start, in plural words too; anything else told what is accepted."""
import pytest

from spinorbit.base.errors import ScenarioError
from spinorbit.edge.scenarios import load_scenario


@pytest.mark.parametrize("end", ["2000-13-45", "2030-01-01T00:00:00 UTC", "yesterday", "3 fortnights ago"])
def test_a_bad_end_date_is_told_that_iso_dates_and_durations_are_accepted(end):
    with pytest.raises(ScenarioError) as err:
        load_scenario("free_body", [f"span.end={end}"])
    text = str(err.value)
    assert err.value.key == "span.end" and "an ISO date in TDB without a time zone" in text
    assert "a finite duration from span.start" in text and "'2 days'" in text


@pytest.mark.parametrize("end, days", [("2 days", 2.0), ("2 d", 2.0), ("3 weeks", 21.0), ("1 years", 365.25)])
def test_durations_in_plural_words_are_read(end, days):
    scenario = load_scenario("free_body", [f"span.end={end}"])
    assert scenario.params.span.end - scenario.params.span.start == pytest.approx(days, rel=1e-15)


def test_a_bad_start_date_says_iso_dates_in_tdb():
    with pytest.raises(ScenarioError, match="an ISO date in TDB without a time zone, e.g. '2000-01-01'"):
        load_scenario("free_body", ["span.start=yesterday"])
