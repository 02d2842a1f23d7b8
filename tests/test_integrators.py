"""Integrators: measured order of every fixed-step/splitting method, adaptive tolerances met,
invariants of the splitting, and failure reporting (IntegrationError with partial output)."""
import math

import numpy as np
import pytest
from numba import njit

from spinorbit.analysis.invariants import kinetic_energy
from spinorbit.base.errors import InputError, IntegrationError
from spinorbit.base.rotations import quat_from_euler313
from spinorbit.integrators import METHODS, get_method, simulate
from spinorbit.models.assemblies.idealised import free_body, under_point_masses
from spinorbit.orbits.analytic import CircularOrbits

STEPPED = [m for m in METHODS if get_method(m).kind in ("fixed", "structure-preserving")]
ADAPTIVE = [m for m in METHODS if get_method(m).kind == "adaptive"]
HLW_MOMENTS = np.array([2 / 3, 1.0, 2.0])
HLW_OMEGA0 = np.array([math.sin(1.1), 0.0, math.cos(1.1)]) / HLW_MOMENTS


@pytest.fixture(scope="module")
def torqued():
    """A smooth torqued problem: asymmetric body, one point mass on an inclined circle (P91 torque)."""
    orbit = CircularOrbits(("m",), gm=[0.5], radius=[1.0], rate=[1.0], inclination=[0.3])
    moments = np.array([0.8, 1.0, 1.3])
    system = under_point_masses(moments, orbit, quat_from_euler313(0.2, 0.5, 0.1), [0.3, -0.4, 1.2])
    t = np.linspace(0.0, 20.0, 11)
    reference = simulate(system, t, "rk8", {"step": 0.01}, estimate_error=False)[0].y          # converged: error ~1e-14
    return system, t, reference


def test_every_method_states_its_order():
    for name in METHODS:
        cls = get_method(name)
        assert cls.name == name
        assert cls.kind == "adaptive" or isinstance(cls.order, int)


@pytest.mark.parametrize("method", STEPPED)
def test_convergence_order(method, torqued):
    """Measured order from steps h and h/2 (powers of two, in the asymptotic range) within 0.3 of the stated one."""
    system, t, reference = torqued
    order = get_method(method).order
    h = 2.0 ** round(math.log2(0.1 * 2 ** ((order - 2) / 2)))     # order 2: 1/8, 4: 1/4, 8: 1
    errors = [np.abs(simulate(system, t, method, {"step": step}, estimate_error=False)[0].y - reference).max()
              for step in (h, h / 2)]
    measured = math.log2(errors[0] / errors[1])
    assert abs(measured - order) < 0.3, f"{method}: measured order {measured:.2f}, errors {errors}"


@pytest.mark.parametrize("method", ADAPTIVE)
@pytest.mark.parametrize("rtol", [1e-8, 1e-10])
def test_adaptive_reaches_tolerance(method, rtol, torqued):
    """Global error over 20 time units within 10 x rtol of the converged state (|y| ~ 1)."""
    system, t, reference = torqued
    options = {"tolerance": rtol} if method == "taylor" else {"rtol": rtol, "atol": rtol * 1e-2}
    solution = simulate(system, t, method, options, estimate_error=False)[0]
    assert np.abs(solution.y - reference).max() < 10 * rtol


@pytest.mark.parametrize("method", ["strang", "yoshida4", "suzuki4"])
def test_splitting_keeps_invariants_of_free_body(method):
    """Torque-free HLW body, 1e5 steps: |L| to rounding; energy error bounded, no secular growth."""
    system = free_body(HLW_MOMENTS, np.array([1.0, 0, 0, 0]), HLW_OMEGA0)
    t = np.linspace(0.0, 1e4, 2001)
    y = simulate(system, t, method, {"step": 0.1}, estimate_error=False)[0].y
    l_norm = np.linalg.norm(HLW_MOMENTS * y[:, 4:7], axis=1)
    assert np.abs(l_norm - 1.0).max() < 1e-13
    energy_error = np.abs(kinetic_energy(HLW_MOMENTS, y[:, 4:7]) / kinetic_energy(HLW_MOMENTS, HLW_OMEGA0) - 1)
    first, last = energy_error[:200].max(), energy_error[-200:].max()
    assert last < 1.5 * first                   # bounded: the last tenth no worse than the first
    assert np.abs(np.linalg.norm(y[:, :4], axis=1) - 1).max() < 1e-14


def test_symmetric_free_flow_beats_axes_splitting_for_fast_nearly_symmetric_spinner():
    """Earth-like spinner (C-A)/C = 3.3e-3, B-A = 1e-5 A, 1 rev/d, distant perturber: the three-axis
    Strang splitting's error grows with the spin, the symmetric-exact one does not."""
    orbit = CircularOrbits(("sun",), gm=[2.96e-4], radius=[1.0], rate=[0.0172], inclination=[0.41])
    moments = np.array([1.0, 1.00001, 1.0033])
    system = under_point_masses(moments, orbit, [1.0, 0, 0, 0], [1e-4, 0, 2 * math.pi])
    t = np.linspace(0.0, 30.0, 31)
    reference = simulate(system, t, "rk8", {"step": 0.01}, estimate_error=False)[0].y
    error = {flow: np.abs(simulate(system, t, "strang", {"step": 0.05, "free_flow": flow},
                                   estimate_error=False)[0].y - reference).max() for flow in ("symmetric", "axes")}
    assert error["symmetric"] < 1e-6
    assert error["axes"] > 1e3 * error["symmetric"], error


def test_splitting_needs_a_torque():
    system = free_body(HLW_MOMENTS, np.array([1.0, 0, 0, 0]), HLW_OMEGA0)
    system.torque = None
    with pytest.raises(InputError, match="^method: got .strang."):
        simulate(system, [0.0, 1.0], "strang", estimate_error=False)[0]
    with pytest.raises(InputError, match="^free_flow: got .exact."):
        simulate(free_body(HLW_MOMENTS, np.array([1.0, 0, 0, 0]), HLW_OMEGA0), [0.0, 1.0], "strang",
                 {"free_flow": "exact"}, estimate_error=False)


@njit
def _positions_blow_up(t, data):
    """One mass at ``data`` (3,) until t = 5, then nowhere (NaN): the torque becomes non-finite."""
    out = np.empty((1, 3))
    for k in range(3):
        out[0, k] = np.nan if t > 5.0 else data[k]
    return out


class BlowingUp:
    """An orbit source (names, gm, kernel, data) whose one mass leaves the reals after t = 5."""

    names, gm, data = ("m",), np.array([1e-3]), np.array([3.0, 1.0, 2.0])
    kernel = staticmethod(_positions_blow_up)


@pytest.mark.parametrize("method", ["rk8", "rk4", "strang", "dop853"])
def test_failure_raises_integration_error_with_partial_solution(method):
    system = under_point_masses(HLW_MOMENTS, BlowingUp(), [1.0, 0, 0, 0], HLW_OMEGA0)
    t = np.linspace(0.0, 10.0, 11)
    options = {"step": 0.1} if method != "dop853" else {}
    with pytest.raises(IntegrationError) as info:
        simulate(system, t, method, options, estimate_error=False)[0]
    err = info.value
    assert 5.0 - 1e-9 <= err.t <= 6.0 and err.y.shape == (7,)
    assert "step" in str(err) or "torque" in str(err)           # advice given
    assert 4.0 <= err.partial.t[-1] <= err.t and np.all(np.isfinite(err.partial.y))


def test_bench_writes_work_precision_table(tmp_path):
    """spinorbit bench on the HLW body (1000 d): files written; rk8 reaches 1e-9 rad vs the closed form."""
    from spinorbit.edge.bench import bench_scenario

    scene = __import__("pathlib").Path(__file__).parent.parent / "scenarios" / "free_body.toml"
    rows, paths = bench_scenario(scene, ["rk8", "strang"], tmp_path, budget_s=0.5)
    assert all(p.exists() for p in paths)
    assert min(r["error_rad"] for r in rows if r["method"] == "rk8") < 1e-9
    assert {r["method"] for r in rows} == {"rk8", "strang"}


def test_rk8_step_does_not_depend_on_output_cadence():
    """Outputs closer than the step come from DOP853's continuous extension, as accurate as the steps."""
    from spinorbit.analysis.theory import FreeRigidBody
    from spinorbit.base.rotations import quat_angle

    moments = np.array([2 / 3, 1.0, 2.0])
    omega0 = np.array([math.sin(1.1), 0.0, math.cos(1.1)]) / moments
    system = free_body(moments, [1.0, 0, 0, 0], omega0)
    exact = FreeRigidBody(moments, omega0, np.array([1.0, 0, 0, 0]))
    coarse_t, fine_t = np.arange(0, 200, 0.4), np.arange(0, 200, 0.013)
    coarse = simulate(system, coarse_t, "rk8", {"step": 0.2}, estimate_error=False)[0]
    fine = simulate(system, fine_t, "rk8", {"step": 0.2}, estimate_error=False)[0]
    assert fine.nsteps == math.ceil(fine_t[-1] / 0.2 - 1e-9)     # the step is not cut to the cadence
    error_coarse = quat_angle(coarse.quaternion, exact.attitude(coarse_t)).max()
    error_fine = quat_angle(fine.quaternion, exact.attitude(fine_t)).max()
    assert error_coarse < 1e-9 and error_fine < 1.2 * error_coarse


@pytest.mark.parametrize("t_out", [5.0, [], [1.0, math.nan], [1.0, 3.0, 2.0], [[1.0, 2.0]]])
def test_bad_output_times_get_one_clear_error(t_out, torqued):
    """A scalar, an empty, non-finite, back-and-forth or 2-d set of output times is refused by name."""
    with pytest.raises(InputError, match=r"^t_out: got .*expected a 1-d array of finite times"):
        get_method("rk8")(step=0.1).solve(torqued[0], t_out)          # the contract, below the door's splitting


def test_rk8_runs_one_compiled_loop_whatever_the_layout_of_the_output_times(torqued):
    """Output times given as a strided view (every other output, as the error estimate's coarse run takes them)
    run the loop compiled for contiguous ones: one specialisation, not one per array layout (each costs seconds)."""
    from spinorbit.base import rotations
    from spinorbit.base.linker import link
    from spinorbit.integrators.rk8 import rk_fixed, rk_step

    system, t = torqued[0], np.linspace(0.0, 50.0, 1001)
    simulate(system, t, "rk8", {"step": 0.05}, estimate_error=False)[0]
    simulate(system, t[::2], "rk8", {"step": 0.1}, estimate_error=False)[0]
    step = link(rk_step, rhs=system.rhs, put=rotations.put)
    assert len(link(rk_fixed, rk_step=step, put=rotations.put).signatures) == 1


@pytest.mark.parametrize("method, options", [("rk8", {"step": 0.05}), ("rk4", {"step": 0.005}),
                                             ("strang", {"step": 0.05}), ("suzuki4", {"step": 0.05}),
                                             ("dop853", {"rtol": 1e-13, "atol": 1e-15})])
def test_forward_then_backward_returns_to_the_start(method, options, torqued):
    """Run to t = 20 and back (a descending span) on the torqued problem: the start comes back at the method's
    floor.  Splittings are time-symmetric (the backward step inverts the forward one), so they return to rounding
    whatever the step; rk8 at h = 0.05, rk4 at 0.005 and dop853 at rtol 1e-13 carry ~1e-12 truncation error each way."""
    system, t, _ = torqued
    there = simulate(system, t, method, options, estimate_error=False)[0]
    back = system.with_start(t[-1], there.y[-1])
    returned = simulate(back, t[::-1], method, options, estimate_error=False)[0]
    assert np.allclose(returned.t, t[::-1])
    attitude = 2 * np.arcsin(min(1.0, np.linalg.norm(returned.y[-1, :4] - system.y0[:4] * np.sign(
        returned.y[-1, :4] @ system.y0[:4])) / 2))
    assert attitude < 1e-9                                            # rad
    assert np.abs(returned.y[-1, 4:7] - system.y0[4:7]).max() < 1e-9 * np.abs(system.y0[4:7]).max()
    assert np.allclose(returned.y[::-1], there.y, rtol=0, atol=1e-8)  # the same path both ways


@njit
def _positions_blow_up_before(t, data):
    """One mass at ``data`` (3,) after t = -5, nowhere (NaN) before it."""
    out = np.empty((1, 3))
    for k in range(3):
        out[0, k] = np.nan if t < -5.0 else data[k]
    return out


class BlowingUpBefore(BlowingUp):
    kernel = staticmethod(_positions_blow_up_before)


@pytest.mark.parametrize("method", ["rk8", "rk4", "strang", "dop853"])
def test_a_backward_failure_reports_where_it_happened(method):
    """Integrated backward, the failure is reported at the last finite time reached (-5), not at the start."""
    system = under_point_masses(HLW_MOMENTS, BlowingUpBefore(), [1.0, 0, 0, 0], HLW_OMEGA0)
    t = np.linspace(0.0, -10.0, 11)
    options = {"step": 0.1} if method != "dop853" else {}
    with pytest.raises(IntegrationError) as info:
        simulate(system, t, method, options, estimate_error=False)[0]
    err = info.value
    assert -6.0 <= err.t <= -5.0 + 1e-9 and err.y.shape == (7,)
    assert err.t <= err.partial.t[-1] <= -4.0 and np.all(np.isfinite(err.partial.y))
