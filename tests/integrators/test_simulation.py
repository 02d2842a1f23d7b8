"""simulate(): the one integrator door estimates its integration error on any System, read off the layout."""
import numpy as np
import pytest

from spinorbit.base.errors import InputError
from spinorbit.bodies import earth
from spinorbit.integrators import simulate
from spinorbit.integrators.simulation import differences
from spinorbit.models.assemblies.earth_moon import closed
from spinorbit.models.assemblies.idealised import free_body
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


def test_the_runs_are_each_sides_distinct_times_away_from_t0():
    """Equal output times split into one run of distinct times on their side (the split once recursed for ever on
    a descending span's ties), an output at t0 heads the first run, and none is made of t0 alone."""
    from spinorbit.integrators.simulation import away_from

    assert [run.tolist() for run in away_from(0.0, np.array([-1.0, -2.0, -2.0, -3.0]))] == [[-1, -2, -3]]
    both = away_from(0.0, np.array([2.0, -1.0, 0.0, -1.0, 1.0, 2.0, 0.0]))
    assert [run.tolist() for run in both] == [[0, 1, 2], [-1]]
    assert [run.tolist() for run in away_from(0.0, np.array([-2.0, 0.0, -1.0]))] == [[0, -1, -2]]
    assert away_from(0.0, np.array([0.0, 0.0])) == []


SYMMETRIC = np.array([1.0, 1.0, 2.0])          # A = B, C: the free top's closed form
OMEGA0 = np.array([0.3, 0.4, 1.0])


def free_top_omega(t):
    """The free symmetric top's body rates (Euler §808 for A = B): the equatorial part turns at
    (C - A)/A omega_3 about the figure axis, omega_3 constant."""
    turn = (OMEGA0[0] + 1j * OMEGA0[1]) * np.exp(1j * (SYMMETRIC[2] - SYMMETRIC[0]) / SYMMETRIC[0] * OMEGA0[2] * t)
    return np.column_stack([turn.real, turn.imag, np.full(t.size, OMEGA0[2])])


@pytest.mark.parametrize("method, options", [("dop853", {}), ("rk8", {"step": 0.05})])
def test_outputs_in_any_order_repeated_and_at_t0(method, options):
    """Outputs shuffled, repeated, at t0 and on both sides of it: every row is the closed form at its time
    (|omega| ~ 1: a relative 1e-9, far above either method's error here), the rows at t0 are the start state,
    and the error estimate is a number for each kind."""
    system = free_body(SYMMETRIC, np.array([1.0, 0.0, 0.0, 0.0]), OMEGA0)
    t = np.array([0.0, -1.5, -1.5, 2.0, 0.0, -3.0, 2.0, 0.5])
    solution, point = simulate(system, t, method, options)
    assert np.abs(solution.part("body.omega") - free_top_omega(t)).max() < 1e-9
    assert np.array_equal(solution.y[t == 0.0], np.vstack([system.y0, system.y0]))
    assert np.array_equal(solution.t, t)
    assert 0.0 < point["integration_error_attitude_arcsec"] < 1e-3 and 0.0 < point["integration_error_omega_rel"] < 1e-9


@pytest.mark.parametrize("method", ["dop853", "rk8"])
def test_outputs_only_at_t0_are_the_start_state_with_no_run(method):
    """Every output at t0 (a backward span asked at its start only): the start state, nothing integrated, each
    estimated error exactly zero (scipy once gave no row for it, and the estimate failed on no rows)."""
    system = free_body(SYMMETRIC, np.array([1.0, 0.0, 0.0, 0.0]), OMEGA0, t0=-4.0)
    solution, point = simulate(system, [-4.0, -4.0], method, {"step": 0.05} if method == "rk8" else {})
    assert np.array_equal(solution.y, np.vstack([system.y0, system.y0])) and solution.t.tolist() == [-4.0, -4.0]
    assert point["rhs_evaluations"] == 0 and point["steps"] == 0 and point["method"] == method
    assert point["integration_error_attitude_arcsec"] == 0.0 and point["integration_error_omega_rel"] == 0.0


@pytest.mark.parametrize("t_out", [[], [[0.0, 1.0]], [0.0, np.nan]])
def test_output_times_that_are_not_a_finite_list_are_refused(t_out):
    system = free_body(SYMMETRIC, np.array([1.0, 0.0, 0.0, 0.0]), OMEGA0)
    with pytest.raises(InputError, match="t_out"):
        simulate(system, np.array(t_out, dtype=float), "rk8", {"step": 0.05})


def test_a_run_on_both_sides_of_t0_names_each_side_in_its_progress(monkeypatch, capsys):
    """Two runs from t0, one each way: their progress lines say which, not the same label twice."""
    from spinorbit.base import progress

    monkeypatch.setattr(progress, "DELAY_S", 0.0)
    monkeypatch.delenv("SPINORBIT_QUIET", raising=False)
    system = free_body(SYMMETRIC, np.array([1.0, 0.0, 0.0, 0.0]), OMEGA0)
    simulate(system, np.linspace(-2.0, 2.0, 9), "rk8", {"step": 0.01}, estimate_error=False, label="spin")
    said = capsys.readouterr().err
    assert "spin (backward):" in said and "spin (forward):" in said
