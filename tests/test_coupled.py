"""The closed Earth-Moon system (spinorbit.coupled): action equals reaction for the assembled system,
each term's interaction energy against its force, conservation of the total angular momentum and
energy at the rounding floor, and the two-body Kepler orbit with the figures off."""
import math

import numpy as np
import pytest

from spinorbit import coupled
from spinorbit.bodies import earth
from spinorbit.bodies.moon import de421
from spinorbit.integrators.rk8 import fixed_step
from spinorbit.rotations import matrix_from_quat
from spinorbit.terms import harmonics, point_mass

EPS = np.finfo(float).eps
NO_STATE = np.zeros(7)
RNG = np.random.default_rng(11)


def random_state():
    """A state with the Moon 360 000-410 000 km away in any direction, any attitudes, lunar and daily spins."""
    r = RNG.normal(size=3)
    r *= RNG.uniform(3.6e5, 4.1e5) / np.linalg.norm(r)
    q_m, q_e = RNG.normal(size=4), RNG.normal(size=4)
    w_m = 0.23 * np.array([0.01, -0.02, 1.0]) * RNG.uniform(0.5, 1.5, 3)
    w_e = earth.ERA_RATE_RAD_D * np.array([1e-6, -2e-6, 1.0])
    return coupled.state(r, RNG.normal(size=3) * 5e4, q_m / np.linalg.norm(q_m), w_m, q_e / np.linalg.norm(q_e), w_e)


@pytest.fixture(scope="module")
def params():
    return coupled.parameters()


def test_total_torque_of_the_closed_system_vanishes(params):
    """r x F_moon + R_m N_m + R_e N_e = 0 (the force on the Earth is -F_moon, so the total force is zero
    by construction): every figure torque is balanced by the moment of its reaction force, to rounding
    (measured 8 eps, bound 64 eps of the largest part, the Earth's figure torque ~1e17 G-scaled)."""
    for _ in range(8):
        y = random_state()
        force, n_m, n_e = coupled.interactions(y, params)
        parts = [np.cross(y[:3], force), matrix_from_quat(y[6:10]) @ n_m, matrix_from_quat(y[13:17]) @ n_e]
        scale = max(np.linalg.norm(part) for part in parts)
        assert np.linalg.norm(sum(parts)) < 64 * EPS * scale


def test_each_interaction_is_on_alone_and_off_exactly(params):
    """The balance above is not 0 = 0: each interaction alone pulls and turns (the degree-2 torque on
    each body within the P91 bound 3 GM/r^3 (C - A)/2, §815), and with every figure off nothing does."""
    y = random_state()
    gm, moments_m, moments_e = params[:3]
    r3 = np.linalg.norm(y[:3]) ** 3
    for name in coupled.FIGURES:
        force, n_m, n_e = coupled.interactions(y, coupled.parameters((name,)))
        assert np.linalg.norm(force) > 0 and np.linalg.norm(n_m) + np.linalg.norm(n_e) > 0, name
    _, n_m, _ = coupled.interactions(y, coupled.parameters(("moon_figure",)))
    assert np.linalg.norm(n_m) <= 1.5 * gm[0] / r3 * (moments_m[2] - moments_m[0]) * (1 + 1e-12)
    _, _, n_e = coupled.interactions(y, coupled.parameters(("earth_figure",)))
    assert np.linalg.norm(n_e) <= 1.5 * gm[1] / r3 * (moments_e[2] - moments_e[0]) * (1 + 1e-12)
    for part in coupled.interactions(y, coupled.parameters(())):
        assert not part.any()


def _minus_gradient(energy, r, step):
    return np.array([-(energy(r + step * e) - energy(r - step * e)) / (2 * step) for e in np.eye(3)])


ROT = matrix_from_quat(np.array([0.8, 0.1, -0.3, 0.5]))
R = np.array([[3.1e5, -2.2e5, 0.4e5]])


def test_point_mass_energy_gradient_is_the_force():
    """MacCullagh's energy -GM (r^2 tr I - 3 r.I r)/(2 r^5): minus its central-difference gradient is the
    §818 force (the finite difference good to ~1e-8 at a 10 km step)."""
    inertia, gm = np.diag(de421().moments) + 1e-5 * np.array([[0, 1, 2], [1, 0, 3], [2, 3, 0]]), np.array([2.9e15])
    force = point_mass.force(0.0, NO_STATE, ROT, inertia, R, gm, ())[0]
    numeric = _minus_gradient(lambda r: point_mass.energy(0.0, NO_STATE, ROT, inertia, r[None], gm, ()), R[0], 10.0)
    assert np.abs(force - numeric).max() < 1e-7 * np.abs(force).max()


@pytest.mark.parametrize("body", ["moon", "earth"])
def test_harmonics_energy_gradient_is_the_force(params, body):
    """The degree 3-4 field's energy -(GM/R^2) W: minus its gradient is the term's force (the Moon's
    DE421 field; the Earth's J3, J4)."""
    field = params[3] if body == "moon" else params[4]
    gm = np.array([2.9e15])
    force = harmonics.force(0.0, NO_STATE, ROT, np.eye(3), R, gm, field)[0]
    numeric = _minus_gradient(lambda r: harmonics.energy(0.0, NO_STATE, ROT, np.eye(3), r[None], gm, field), R[0], 10.0)
    assert np.abs(force - numeric).max() < 1e-6 * np.abs(force).max()


# --- runs ---------------------------------------------------------------------------------

SPAN_D, STEP_D = 182.625, 0.05           # half a year; the Earth turns 0.3 rad a step


@pytest.fixture(scope="module")
def start():
    """DE421's Earth-Moon state and lunar orientation at J2000, the Earth on the IAU pole."""
    from spinorbit.orbits.kernel import open_ephemeris
    from spinorbit.references import erfa_pole, moon_de421

    pos, vel = open_ephemeris("de421", 0.0, 0.0).relative_states("moon", "earth", [0.0])
    moon = moon_de421.initial_state(0.0)
    q_e, w_e = coupled.attitude_with_pole(erfa_pole.cip_vector(0.0), earth.ERA_RATE_RAD_D)
    return coupled.state(pos[0], vel[0], moon[:4], moon[4:7], q_e, w_e)


@pytest.fixture(scope="module")
def drifts(start, params):
    t = np.linspace(0.0, SPAN_D, 101)
    return {h: coupled.drifts(fixed_step(coupled.rhs, params, 0.0, start, t, h), params) for h in (STEP_D, STEP_D / 2)}


def test_angular_momentum_and_energy_are_conserved_to_rounding(drifts):
    """Half a year of the full system at h = 0.05 and 0.025 d.  RK8's truncation in the orbit
    ((n h)^9 ~ 4e-18 a step) and in the spins ((w_e h / 2)^9 / 9! ~ 2e-13 a step, a phase error of the
    axisymmetric Earth's turn that leaves L and E alone) is below rounding; what remains is the
    rounding of y + h sum b k, a few eps per step, random-walking over the N = 3650-7300 steps:
    ~eps sqrt(N) = 2e-14.  Bound: 4 eps sqrt(N) at the finer step (7e-14); and halving the step does
    not lower the drift (it would fall 2^8-fold if truncation dominated)."""
    n_steps = SPAN_D / (STEP_D / 2)
    bound = 4 * EPS * math.sqrt(n_steps)
    for h, drift in drifts.items():
        for name, value in drift.items():
            assert value < bound, (h, name, value, bound)
    coarse, fine = drifts[STEP_D], drifts[STEP_D / 2]
    assert coarse["L_vector_rel_drift"] < 4 * fine["L_vector_rel_drift"] + 10 * EPS


def kepler(gm, r0, v0, t):
    """Two-body relative position at times t, closed form (Kepler's equation, f and g functions)."""
    r0n = np.linalg.norm(r0)
    a = 1.0 / (2.0 / r0n - v0 @ v0 / gm)
    n = math.sqrt(gm / a**3)
    e_cos, e_sin = 1.0 - r0n / a, r0 @ v0 / math.sqrt(gm * a)
    out = []
    for dt in t:
        m = n * dt
        de = m
        for _ in range(50):                       # Newton on dE - e_cos sin dE + e_sin (1 - cos dE) = M
            f = de - e_cos * math.sin(de) + e_sin * (1 - math.cos(de)) - m
            de -= f / (1 - e_cos * math.cos(de) + e_sin * math.sin(de))
        f_fun = 1.0 - a / r0n * (1.0 - math.cos(de))
        g_fun = dt - (de - math.sin(de)) / n
        out.append(f_fun * r0 + g_fun * v0)
    return np.array(out)


def test_figures_off_is_the_kepler_orbit(start):
    """With every figure off the relative orbit is Kepler's with GM_e + GM_m: half a year (6.7 orbits,
    mean anomaly M = 42 rad) agrees to rounding.  The rounding walk of the energy, eps sqrt(N) over
    N = 3650 steps, moves the mean motion by 1.5 times that and the phase by M 1.5 eps sqrt(N) = 1.2e-12
    (measured 1.2e-12); bound 1e-11 relative (4 mm)."""
    p = coupled.parameters(())
    t = np.linspace(0.0, SPAN_D, 51)
    ys = fixed_step(coupled.rhs, p, 0.0, start, t, STEP_D)
    exact = kepler(p[0].sum(), start[:3], start[3:6], t)
    error = np.linalg.norm(ys[:, :3] - exact, axis=1) / np.linalg.norm(exact, axis=1)
    assert error.max() < 1e-11


def test_the_stress_scene_reports_the_drifts_and_judges_only_a_decade():
    """scenarios/stress/coupled_conservation.toml over 20 days: the drifts it reports are at rounding
    (4 eps sqrt(N), N = 400 steps), and a span under 10 yr is not judged."""
    from pathlib import Path

    from spinorbit.results import run_scenario

    path = Path(__file__).parents[1] / "scenarios" / "stress" / "coupled_conservation.toml"
    summary = run_scenario(path, ['span.end="20 d"', "output.plots=false"]).summary
    for name in ("L_norm_rel_drift", "L_vector_rel_drift", "energy_rel_drift"):
        assert summary["comparison"][name] < 4 * EPS * math.sqrt(400)
    assert summary["comparison"]["passed"] is None and summary["verdict"]["result"] == "not-compared"
