"""Moon and Earth scenes under ``spinorbit bench``: build(), their torques, and the splittings on them."""
from pathlib import Path

import numpy as np
import pytest

from spinorbit.edge.scenarios import load_scenario
from spinorbit.integrators import simulate
from spinorbit.models import System
from spinorbit.models.interactions import GeodesicRate
from spinorbit.models.spin import euler_omega_dot

SCENARIOS = Path(__file__).parents[2] / "scenarios"


def test_moon_rigid_levels_expose_the_torque_of_their_rhs():
    """Levels 1-2: system.torque is the rhs's torque (Euler's equations §813 with it give the rhs); level 3:
    none."""
    from spinorbit.starts.moon import build_system

    scenario = load_scenario(SCENARIOS / "moon_libration.toml", ['span.end="4 d"', "model.level=2"])
    system, _ = build_system(scenario.params, scenario.params.orbit.source)
    omega = system.layout["moon.omega"]
    y = system.y0.copy()
    y[omega] *= 1.0 + np.array([1e-3, -2e-3, 5e-4])            # away from DE421's state too
    for t in (system.t0 + 0.3, system.t0 + 2.7):
        expected = euler_omega_dot(system.moments, y[omega], system.torque(t, y, system.params))
        got = system.rhs(t, y, system.params)[omega]
        assert np.abs(got - expected).max() < 1e-12 * np.abs(expected).max()
    level3 = load_scenario(SCENARIOS / "moon_libration.toml", ['span.end="4 d"']).params
    level3, _ = build_system(level3, level3.orbit.source)
    assert level3.torque is None and level3.layout.names == ["moon.q", "moon.omega", "moon.omega_core"]
    assert level3.y0.size == 10


def test_earth_full_bench_splitting_matches_rk8_with_geodesic_precession(tmp_path):
    """Full Earth, 30 d: suzuki4 (symmetric free flow + exact frame rotation) vs the converged rk8 run.

    Without the frame rate the split run misses the geodesic precession, 1.92"/cy x 30 d = 7.6e-9 rad.
    """
    from spinorbit.edge.bench import bench_scenario
    from spinorbit.scenes.earth_precession_nutation import SCENE

    overrides = ['span.end="30 d"', 'earth.start_pole="iau"']
    rows, paths = bench_scenario(SCENARIOS / "earth_precession_nutation_full.toml", ["suzuki4"], tmp_path,
                                 budget_s=0.05, overrides=overrides)
    assert all(p.exists() for p in paths)
    assert min(r["error_rad"] for r in rows) < 1e-11            # measured 1.4e-12 (h = 0.0625 d)

    scenario = load_scenario(SCENARIOS / "earth_precession_nutation_full.toml", overrides)
    t = scenario.output_times()
    model = SCENE.build(scenario.params, t)
    system, error = model.system, SCENE.bench(scenario.params, model, t)
    assert system.meta["reference_agreement_rad"] < 1e-11                   # measured 4.6e-12 rad
    without = System(system.name, list(system.bodies.values()), system.motion,
                     [i for i in system.interactions if not isinstance(i, GeodesicRate)], system.t0)
    without.y0 = system.y0
    solution, _ = simulate(without, t, "suzuki4", {"step": 0.125}, estimate_error=False)
    assert error(solution) == pytest.approx(7.6e-9, rel=0.05)   # measured 7.64e-9
