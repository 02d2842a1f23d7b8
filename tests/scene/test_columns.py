"""Every column a scene writes explains itself: an astropy description (spinorbit.scene.columns) in its table and
ECSV."""
import pytest

from spinorbit.edge import catalogue
from spinorbit.edge.runner import run_scenario
from spinorbit.scene.columns import COLUMNS

# One short run of every scene kind that writes a table (its own span shortened where the scene allows).
SHORT = {"free_body": ["span.end=20 d"], "p92_general": [], "p93_bounded": [], "p94_moonlike": [],
         "p95_symmetric": [], "p96_earthlike": [], "stress/mercury_3_2": [],
         "moon_libration": ["span.end=1900-03-01T00:00:00"], "earth_precession_nutation": ["span.end=1951-01-01"],
         "earth_moon_coupled": ["span.end=1950-03-01T00:00:00"], "stress/coupled_conservation": ["span.end=60 d"],
         "earth_deep_time": ["span.end=-10 kyr"],
         "mercury_spin": ["span.start=2000-01-01", "span.end=2000-07-01", "precession.scales=[]"]}


@pytest.mark.parametrize("scene", sorted(SHORT))
def test_every_column_of_a_scene_is_described(scene):
    table = run_scenario(catalogue.names()[scene], SHORT[scene]).table
    undescribed = [name for name in table.colnames if not table[name].info.description]
    assert not undescribed, (f"{scene}: columns without a description: {undescribed} "
                             "(add them to spinorbit.scene.columns)")


def test_descriptions_say_something():
    assert all(len(text) >= 3 for text in COLUMNS.values())
