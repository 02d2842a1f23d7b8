"""A stored scene's model over a stretch (spinorbit.solutions.stretches): read off its Scene's ``stored``.

References: DE421's lunar orientation at J2000 (its libration series, references.moon_de421), where the Moon's
stored solution starts; the span and start asked for a stretch."""
import numpy as np
import pytest

from spinorbit.base.errors import InputError
from spinorbit.edge.scenarios import load_scenario
from spinorbit.solutions import stretches
from tests.units import arcsec

uas = arcsec * 1e-6


def test_the_moons_first_run_starts_at_its_anchor_on_de421s_orientation():
    """The Moon's solution starts at its anchor, J2000, from DE421's orientation there (within 1 uas), whatever
    span the scenario asks (its own: 1900-2050)."""
    from spinorbit.analysis.librations import icrf_to_body, pole_and_longitude_difference
    from spinorbit.references.moon_de421 import Orientation

    scenario = load_scenario("moon_libration")
    t0, y0 = stretches.first_start(scenario)
    system = stretches.system(stretches.stretch(scenario, t0, t0 + 4.0, t0), (t0, y0))
    mats = icrf_to_body(y0[system.layout["moon.q"]][None, :])
    pole, longitude = pole_and_longitude_difference(mats, Orientation()(np.array([0.0]))["icrf_to_body"])
    assert t0 == 0.0
    assert abs(pole[0]) < 1 * uas and abs(longitude[0]) < 1 * uas


def test_a_stretch_holds_its_span_and_start_and_a_scene_kept_as_none_is_refused():
    """A stretch [8, 16] d started at 4 d: the span asked, the Moon's model.start at 4 d (its scene's
    ``started``), the run's checkpoint and extra output times left behind; a scene that keeps no solution is
    refused in one line naming those that do."""
    scenario = load_scenario("moon_libration")
    scenario.extra_times = np.array([9.5])
    stretch = stretches.stretch(scenario, 8.0, 16.0, 4.0)
    assert stretch.params.span.bounds == (8.0, 16.0) and stretch.params.model.start == 4.0
    assert stretch.extra_times is None and stretch.checkpoint is None
    assert scenario.params.model.start is None                  # the scenario itself unchanged
    with pytest.raises(InputError, match="a scene kept as a solution: .*'moon_libration'"):
        stretches.stored(load_scenario("free_body"))
