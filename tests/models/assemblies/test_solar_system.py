"""The solar system as one System (spinorbit.models.assemblies.solar_system): action equals reaction, the closed
system's momentum, angular momentum and energy at the Taylor integrator's floor, and DE421's model started from
DE421's initial conditions staying with DE421 over a year."""
import numpy as np
import pytest

from spinorbit.base.constants import J2000_JD
from spinorbit.base.rotations import cross3, matrix_from_quat
from spinorbit.bodies import earth
from spinorbit.bodies.de421_header import header
from spinorbit.integrators import simulate
from spinorbit.models.assemblies.solar_system import SUN_SPIN_RAD_D, closed, solar_system
from spinorbit.models.interactions import Newton
from spinorbit.models.start import solar_system_de421
from spinorbit.models.system import System
from spinorbit.references.erfa_pole import cip_vector
from tests.units import mas

EPS = np.finfo(float).eps
T0 = header()["JDEPOC"] - J2000_JD


def started(system):
    system.y0 = system.layout.pack(solar_system_de421(system, T0, cip_vector(T0), earth.ERA_RATE_RAD_D,
                                                      SUN_SPIN_RAD_D))
    return system


@pytest.fixture(scope="module")
def closed_system():
    return started(closed(T0))


def momentum_and_torque(system, y):
    """(sum of GM a over the carried centres, sum of their moments and the spins' rates) from the rhs at y, and
    the sum of the parts' sizes of each (the scale of their rounding)."""
    dy = system.rhs(system.t0, y, system.params)
    motion = system.motion
    n = len(motion.free) + 2
    weights = motion._reduced()
    x, a = y[:6 * n].reshape(n, 6)[:, :3], dy[:6 * n].reshape(n, 6)[:, 3:]
    forces = weights[:, None] * a
    moments = np.array([cross3(xi, fi) for xi, fi in zip(x, forces)])
    q, omega = y[system.layout["moon.q"]], y[system.layout["moon.omega"]]
    inertia = system.bodies["moon"].figure.moments
    moon = matrix_from_quat(q) @ (inertia * dy[system.layout["moon.omega"]] + np.cross(omega, inertia * omega))
    spins = [dy[system.layout["earth.spin"]], dy[system.layout["sun.spin"]], moon]
    parts = [*moments, *spins]
    return (forces[:-1].sum(axis=0), np.linalg.norm(forces[:-1], axis=1).sum(),
            sum(parts), sum(np.linalg.norm(part) for part in parts))


def test_figures_act_with_their_reactions(closed_system):
    """With the point masses' Newton taken out, only the figures act (the Sun's J2 on every body, the Earth's
    and the Moon's with each other, the Sun and the planets): their forces sum to zero and their torques to
    minus the moments of their forces, to rounding (64 eps of the sum of the parts' sizes; measured 14-22 eps), at
    DE421's state and at one with the attitudes turned."""
    figures = System("figures", list(closed_system.bodies.values()), closed_system.motion,
                     [i for i in closed_system.interactions if not isinstance(i, Newton)])
    rng = np.random.default_rng(3)
    for turned in (False, True):
        y = closed_system.y0.copy()
        if turned:
            q = rng.normal(size=4)
            y[figures.layout["moon.q"]] = q / np.linalg.norm(q)
            spin = figures.layout["earth.spin"]
            y[spin] = np.linalg.norm(y[spin]) * np.array([0.3, 0.4, 0.866])
        force, force_scale, torque, torque_scale = momentum_and_torque(figures, y)
        assert force_scale > 0 and torque_scale > 0
        assert np.abs(force).max() <= 64 * EPS * force_scale
        assert np.abs(torque).max() <= 64 * EPS * torque_scale


def test_closed_solar_system_conserves_its_invariants(closed_system):
    """Ten years of the closed solar system (Newton, every figure with its reaction, the Sun turning) with the
    Taylor integrator at 1e-16: momentum (against sum GM |v|), angular momentum and energy change by no more than
    1e-13 (measured 2.5e-15, 1.2e-15, 1.7e-14: the rounding of 2400 steps); RK8 at 0.25 d loses 5e-12 of the
    energy, which the same bound would catch."""
    t = T0 + np.linspace(0.0, 3652.5, 41)[1:]
    solution, _ = simulate(closed_system, t, "taylor", {"tolerance": 1e-16}, estimate_error=False)
    states = np.vstack([closed_system.y0, solution.y])
    energy, momentum = closed_system.invariants(states)
    linear = closed_system.motion.momentum(states)
    n = len(closed_system.motion.free) + 2
    scale = np.sum(closed_system.motion._reduced()[:-1] * np.linalg.norm(states[0, :6 * n].reshape(n, 6)[:-1, 3:],
                                                                         axis=1))
    assert np.linalg.norm(linear - linear[0], axis=1).max() <= 1e-13 * scale
    assert np.linalg.norm(momentum - momentum[0], axis=1).max() <= 1e-13 * np.linalg.norm(momentum[0])
    assert np.abs(energy / energy[0] - 1).max() <= 1e-13


def test_de421s_solar_system_stays_with_de421_over_a_year():
    """DE421's model from DE421's initial conditions (1969-06-28), one year forward with the Taylor integrator:
    the Moon within 0.5 mas and 5 cm of DE421, the lunar pole and longitude within 1 mas (the issue's targets
    over a century are 1 mas and 0.1 m; measured 0.19 mas, 2.7 cm, 0.7 and 0.5 mas over 1968-1972), and the
    inner planets within 100 m (DE421's asteroids move the Earth by ~60 m in 1968-1972; Mars by 1.8 km)."""
    from spinorbit.comparisons import solar_system_de421 as compare

    system = started(solar_system(t0=T0))
    t = T0 + np.arange(1.0, 366.0, 1.0)
    solution, _ = simulate(system, t, "taylor", {"tolerance": 1e-15}, estimate_error=False)
    direction, distance = compare.orbit_errors(t, solution.part("moon.r"))
    _, pole, longitude, _ = compare.lunar(t, solution.part("moon.q"))
    assert direction.max() < 0.5 * mas and np.abs(distance).max() < 5e-5
    assert pole.max() < 1 * mas and np.abs(longitude).max() < 1 * mas
    planets = compare.planet_errors(t, compare.heliocentric(system, solution))
    for name in ("mercury", "venus", "earth"):
        assert planets[name].max() < 0.1, name
    assert planets["mars"].max() < 3.0
