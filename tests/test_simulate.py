"""simulate(): the one integrator door estimates its integration error on any System, read off the layout."""
import numpy as np
import pytest

from spinorbit.bodies import earth
from spinorbit.integrators import simulate
from spinorbit.integrators.simulation import differences
from spinorbit.models.assemblies.earth_moon import closed
from spinorbit.models.start import earth_moon_de421
from spinorbit.references.erfa_pole import cip_vector

KINDS = ("integration_error_attitude_arcsec", "integration_error_omega_rel", "integration_error_position_km",
         "integration_error_moon_v_rel")


@pytest.fixture(scope="module")
def coupled():
    """The closed Earth-Moon system (the Moon's orbit, a rigid Moon, a gyroscopic Earth) from DE421 at J2000:
    (System, 60 d of output times)."""
    system = closed(moon_core=False)
    start = earth_moon_de421(system, 0.0, cip_vector(0.0), earth.ERA_RATE_RAD_D)
    return system.with_start(0.0, system.layout.pack(start)), np.linspace(0.0, 60.0, 31)


def test_the_estimate_reads_every_slice_of_a_coupled_system(coupled):
    """rk8 at 1 d: Richardson's estimate (a run at 2 d, the difference over 2^8 - 1) of the attitudes (the
    Moon's quaternion and the Earth's spin direction, arcsec), the Moon's rates, position and velocity, each
    within a factor 4 of the actual error against a converged run at 1/8 d (measured 1.3-2.3 times: the step
    is in RK8's asymptotic regime, where the ratio goes to 1)."""
    system, t = coupled
    solution, point = simulate(system, t, "rk8", {"step": 1.0})
    assert point["integration_error_method"].startswith("Richardson") and point["step_d"] == 1.0
    converged, _ = simulate(system, t, "rk8", {"step": 0.125}, estimate_error=False)
    actual = differences(system.layout, solution.y, converged.y, 1.0)
    for kind in KINDS:
        assert actual[kind] / 4 < point[kind] < 4 * actual[kind], (kind, point[kind], actual[kind])


def test_without_an_estimate_no_error_is_reported(coupled):
    system, t = coupled
    _, point = simulate(system, t[:3], "rk8", {"step": 1.0}, estimate_error=False)
    assert not any(key.startswith("integration_error") for key in point)
    assert point["method"] == "rk8" and point["steps"] == 4 and point["rhs_evaluations"] == 12 * 4


def test_repeated_output_times_on_a_backward_span_are_one_run():
    """Equal output times before t0 (a backward span asked twice at one date) split into one run away from t0:
    the rows come back in the order given (the split once recursed for ever on them)."""
    from spinorbit.integrators.simulation import away_from

    t_out = np.array([-1.0, -2.0, -2.0, -3.0])
    sides = away_from(0.0, t_out)
    assert len(sides) == 1 and sides[0].tolist() == [0, 1, 2, 3]
    both = away_from(0.0, np.array([2.0, -1.0, -1.0, 1.0, 2.0]))
    assert [side.tolist() for side in both] == [[3, 0, 4], [1, 2]]
