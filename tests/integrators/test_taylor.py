"""The Taylor backend (spinorbit.models.trace, spinorbit.integrators.taylor): the System's generated rhs run on
heyoka expressions gives the compiled rhs's numbers; a Taylor run agrees with the scene's own integrator to the
sum of their error estimates on every scene that takes it; an ephemeris-driven scene refuses it by name."""
import re
from pathlib import Path

import numpy as np
import pytest

from spinorbit.base.errors import IntegrationError, ScenarioError
from spinorbit.base.rotations import quat_angle, quat_from_euler313
from spinorbit.edge.runner import run_scenario
from spinorbit.edge.scenarios import load_scenario, taylor_kinds
from spinorbit.integrators import simulate
from spinorbit.integrators.taylor import heyoka, scales
from spinorbit.models.assemblies.earth_moon import closed
from spinorbit.models.assemblies.idealised import free_body, under_point_masses
from spinorbit.orbits.analytic import CircularOrbits, KeplerOrbit

SCENARIOS = Path(__file__).resolve().parents[2] / "scenarios"
EPS = np.finfo(float).eps


def traced(system, t, y):
    """The derivatives of the System's expressions at (t, y), compiled by heyoka."""
    hy = heyoka()
    variables, derivatives = system.expressions()
    return hy.cfunc(derivatives, variables, compact_mode=True)(y, time=t)


def assert_same_rhs(system, t, y):
    """Each slice of the traced rhs equals the compiled one to rounding (64 eps of the slice's largest part)."""
    exact, symbolic = system.rhs(t, y, system.params), traced(system, t, y)
    for part in system.layout.slices:
        a, b = exact[part.index], symbolic[part.index]
        assert np.abs(a - b).max() <= 64 * EPS * max(np.abs(a).max(), 1e-300), part.name


def test_the_kernels_run_on_expressions_as_they_run_compiled():
    """A rigid body under two masses on a circle and on a Kepler ellipse (heyoka's kepE for the solver), and the
    closed Earth-Moon system (figures, harmonics, figure-figure, core): the same derivatives at three states."""
    rng = np.random.default_rng(5)
    circle = CircularOrbits(("a",), [2.0], [3.0], [0.4], phase=[0.3], inclination=[0.2])
    ellipse = KeplerOrbit(("b",), [1.0], [5.0], [0.3], mean_motion=[0.09], mean_anomaly=[1.0],
                          periapsis=[0.5], inclination=[0.3], node=[1.1])
    for orbit in (circle, ellipse):
        body = under_point_masses(np.array([1.0, 1.3, 1.7]), orbit, [1.0, 0, 0, 0], np.array([0.1, -0.2, 2.0]))
        for t in (0.0, 7.3, -40.1):
            q = rng.normal(size=4)
            assert_same_rhs(body, t, np.concatenate([q / np.linalg.norm(q), rng.normal(size=3)]))
    pair = closed()
    r = rng.normal(size=3)
    y = np.concatenate([3.8e5 * r / np.linalg.norm(r), rng.normal(size=3) * 8e4, [0.6, 0.0, 0.8, 0.0],
                        [1e-5, 2e-5, 0.23], [1e-3, -2e-3, 0.229], [1e16, -3e16, 2.4e23]])
    assert_same_rhs(pair, 100.0, y)


def test_the_state_is_scaled_slice_by_slice_by_powers_of_two():
    """Positions of 4e5 km and a spin of 2.4e23 share one tolerance only scaled (heyoka's norm is the state's
    infinity norm): each slice by the power of two nearest its size, a quaternion not at all."""
    pair = closed()
    y = np.concatenate([[3.8e5, 0, 0], [0, 8.8e4, 0], [1.0, 0, 0, 0], [0, 0, 0.23], [0, 0, 0.229], [0, 0, 2.4e23]])
    factors = scales(pair.layout, y)
    assert set(np.log2(factors)) <= set(range(-80, 81))
    for part in pair.layout.slices:
        size = np.linalg.norm(y[part.index])
        assert np.all(factors[part.index] == 1.0) if part.kind == "quaternion" else \
            np.all(np.abs(np.log2(size / factors[part.index])) <= 0.5), part.name


def test_free_body_against_euler_at_heyokas_floor():
    """Euler's closed form (spinorbit.analysis.theory) over 100 periods of the HLW body at tolerance 1e-15: 1e-11 rad
    (the rounding of 1e4 steps), and the error estimate (a run at 1e-17) says as much."""
    from spinorbit.analysis.theory import FreeRigidBody

    moments, omega0, q0 = np.array([2 / 3, 1.0, 2.0]), np.array([1.0, 0.1, 0.3]), quat_from_euler313(0.1, 0.2, 0.3)
    t = np.linspace(0.0, 1000.0, 1001)[1:]
    solution, point = simulate(free_body(moments, q0, omega0), t, "taylor", {"tolerance": 1e-15})
    error = quat_angle(solution.quaternion, FreeRigidBody(moments, omega0, q0).attitude(t)).max()
    assert error < 1e-11
    assert point["integration_error_attitude_arcsec"] * 4.85e-6 < 1e-11
    assert point["steps"] == point["rhs_evaluations"] > 0


def test_a_run_does_not_depend_on_when_it_is_sampled():
    """Outputs every 1 d and every 1.5 d of a body turning for 2000 d (9000 steps) are one trajectory at the days
    they share, to rounding (8 eps): one propagation, each step's size from the state alone.  Cut into pieces
    ending on outputs (the integrator before), each run shortened a step at each cut and the two differed by
    2e-11, the size of their integration error."""
    system = free_body(np.array([1.0, 2.0, 3.0]), np.array([1.0, 0, 0, 0]), np.array([0.3, 2.0, 0.4]))
    runs = [simulate(system, np.arange(step, 2000.0 + 1e-9, step), "taylor", {"tolerance": 1e-15},
                     estimate_error=False)[0] for step in (1.0, 1.5)]
    shared = np.intersect1d(runs[0].t, runs[1].t)
    a, b = (run.y[np.isin(run.t, shared)] for run in runs)
    assert shared.size == 666 and np.abs(a - b).max() <= 8 * EPS * np.abs(a).max()


def test_a_collision_is_an_integration_error_with_the_outputs_before_it():
    """The Moon dropped from rest 4e5 km from the Earth falls in pi/(2 sqrt 2) sqrt(r^3/GM) = 5.12 d: heyoka's
    state turns non-finite there, and the error carries the outputs before it (every half day to 5.0 d)."""
    pair = closed(figures=(), moon_core=False)
    pair.y0 = pair.layout.pack({"moon.r": [4e5, 0, 0], "moon.v": [0, 0, 0], "moon.q": [1, 0, 0, 0],
                                "moon.omega": [0, 0, 0.23], "earth.spin": [0, 0, 1e23]})
    fall = np.pi / (2 * np.sqrt(2)) * np.sqrt(4e5 ** 3 / (pair.motion.gm_primary + pair.motion.gm_secondary))
    with pytest.raises(IntegrationError) as caught:
        simulate(pair, np.linspace(0.0, 20.0, 41)[1:], "taylor", {"tolerance": 1e-15}, estimate_error=False)
    assert caught.value.t == pytest.approx(fall, rel=1e-3)
    assert caught.value.partial.t[-1] == 5.0 and np.all(np.isfinite(caught.value.partial.y))


def taylor_copy(name, tmp_path, tolerance=1e-15):
    """The scenario ``name`` with its [integrator] table replaced by the Taylor integrator's."""
    text = (SCENARIOS / f"{name}.toml").read_text()
    text = re.sub(r"\[integrator\][^\[]*", f'[integrator]\nmethod = "taylor"\ntolerance = {tolerance}\n\n', text)
    path = tmp_path / f"{name.replace('/', '_')}.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("name", ["free_body", "p92_general", "p93_bounded", "p94_moonlike", "p96_earthlike"])
def test_both_backends_agree_on_each_scene(name, tmp_path):
    """Each scene that takes Taylor, run with its own integrator and with Taylor at 1e-15: both pass their
    closed forms, and the attitudes differ by no more than 3x the sum of the two runs' error estimates
    (plus 1e-11 rad, the rounding of a run)."""
    overrides = ("output.plots=false", "integrator.estimate_error=true")
    own = run_scenario(SCENARIOS / f"{name}.toml", overrides)
    taylor = run_scenario(taylor_copy(name, tmp_path), overrides)
    assert own.summary["verdict"]["result"] == taylor.summary["verdict"]["result"] == "pass"
    layout = own.states.layout
    difference = max(quat_angle(own.states.y[:, q], taylor.states.y[:, q]).max() for q in layout.quaternions)
    estimates = sum(run.summary["run"]["integration_error_attitude_arcsec"] for run in (own, taylor)) * 4.85e-6
    assert difference <= 3 * estimates + 1e-11


def test_the_closed_earth_moon_system_with_both_backends(tmp_path):
    """The closed Earth-Moon scene (figures, core, gyroscopic Earth): Taylor and its own RK8 at 0.1 d keep the
    invariants within its tolerance, 1e-12 per century, over 10 yr."""
    overrides = ("output.plots=false", 'span.end="2010-01-01T00:00:00"')
    for path in (SCENARIOS / "stress" / "coupled_conservation.toml", taylor_copy("stress/coupled_conservation",
                                                                                 tmp_path)):
        comparison = run_scenario(path, overrides).summary["comparison"]
        assert comparison["passed"] is True, path.name


def test_taylor_is_refused_by_a_scene_that_reads_an_ephemeris():
    """One line naming the key, what was given and the scenes that take it."""
    with pytest.raises(ScenarioError) as caught:
        load_scenario(SCENARIOS / "moon_libration.toml", ('integrator.method="taylor"',))
    message = str(caught.value)
    assert message.startswith("integrator.method: got 'taylor'") and "\n" not in message
    for kind in ("free_body", "coupled_conservation", "solar_system", "p93_planar_libration"):
        assert kind in message and kind in taylor_kinds()
    assert "moon_libration" not in taylor_kinds()


def test_heyoka_caches_under_spinorbits_cache_directory():
    """heyoka's on-disk cache lives beside spinorbit's compiled kernels, private to the user."""
    from spinorbit.base.linker.cache import kernels_dir

    path = Path(heyoka().llvm_state.get_diskcache_path())
    assert path == kernels_dir().parent / "heyoka" and heyoka().llvm_state.get_diskcache_enabled()
    assert path.stat().st_mode & 0o077 == 0
