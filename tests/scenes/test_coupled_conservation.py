"""The closed Earth-Moon system (spinorbit.models.assemblies.earth_moon.closed): action equals reaction for
the assembled System's generated rhs, each interaction's energy against its force, conservation of the total
angular momentum and energy at the rounding floor, and the two-body Kepler orbit with the figures off."""
import math

import numpy as np
import pytest

from spinorbit.base.rotations import matrix_from_quat
from spinorbit.bodies import earth
from spinorbit.integrators.rk8 import fixed_step
from spinorbit.models.assemblies.earth_moon import FIGURES, closed
from spinorbit.models.interactions import Newton, harmonics, point_mass
from spinorbit.models.rotators import Gyroscopic, Rigid
from spinorbit.models.system import System

EPS = np.finfo(float).eps
RNG = np.random.default_rng(11)
ROTATORS = {"rigid": Rigid(), "gyroscopic": Gyroscopic()}


def figures_alone(figures=tuple(FIGURES), earth_rotator="rigid"):
    """The closed assembly's bodies and ``figures`` without the pair's monopole (Newton): the rhs's relative
    acceleration is then the figures' F_moon / m_m - F_earth / m_e alone (rigid Moon, no core)."""
    built = closed(figures, earth_rotator=ROTATORS[earth_rotator], moon_core=False)
    return System("figures alone", list(built.bodies.values()), built.motion,
                  [i for i in built.interactions if not isinstance(i, Newton)])


def random_state(system):
    """A state with the Moon 360 000-410 000 km away in any direction, any attitudes, lunar and daily
    spins."""
    r = RNG.normal(size=3)
    r *= RNG.uniform(3.6e5, 4.1e5) / np.linalg.norm(r)
    q_m, q_e = RNG.normal(size=4), RNG.normal(size=4)
    w_m = 0.23 * np.array([0.01, -0.02, 1.0]) * RNG.uniform(0.5, 1.5, 3)
    w_e = earth.ERA_RATE_RAD_D * np.array([1e-6, -2e-6, 1.0])
    parts = {"moon.r": r, "moon.v": RNG.normal(size=3) * 5e4, "moon.q": q_m, "moon.omega": w_m}
    if "earth.spin" in system.layout:
        parts["earth.spin"] = system.bodies["earth"].figure.moments[2] * matrix_from_quat(q_e) @ w_e
    else:
        parts.update({"earth.q": q_e, "earth.omega": w_e})
    return system.layout.pack(parts)


def actions(system, y):
    """(force on the Moon (inertial), torque on the Moon, torque on the Earth (both inertial)), G-scaled, read
    off the rhs, and the size of the largest term they were read from: F = mu r'' (the figures' forces on the
    two are opposite, so r'' = F_moon / mu), a rigid body's N = R (I w' + w x I w) (Euler §813,
    w x I w = ((C - B) w_y w_z, ...) with the moments' differences, exact for the nearly equal moments, as
    euler_omega_dot takes it), a gyroscopic one's N = l'."""
    dy, parts = system.rhs(0.0, y, system.params), system.layout.split(y)
    gm_e, gm_m = system.bodies["earth"].gm, system.bodies["moon"].gm
    force = gm_e * gm_m / (gm_e + gm_m) * dy[system.layout["moon.v"]]
    terms = [0.0]

    def rigid_torque(name):
        (a, b, c), w = system.bodies[name].figure.moments, parts[f"{name}.omega"]
        w_dot = dy[system.layout[f"{name}.omega"]]
        gyroscopic = np.array([(c - b) * w[1] * w[2], (a - c) * w[2] * w[0], (b - a) * w[0] * w[1]])
        terms.append(np.linalg.norm(gyroscopic))
        return matrix_from_quat(parts[f"{name}.q"]) @ (np.array([a, b, c]) * w_dot + gyroscopic)

    n_e = dy[system.layout["earth.spin"]] if "earth.spin" in system.layout else rigid_torque("earth")
    return force, rigid_torque("moon"), n_e, max(terms)


@pytest.mark.parametrize("figures", [tuple(FIGURES), *((name,) for name in FIGURES)],
                         ids=lambda figures: "+".join(figures))
@pytest.mark.parametrize("earth_rotator", list(ROTATORS))
def test_total_torque_of_the_closed_system_vanishes(earth_rotator, figures):
    """r x F_moon + N_m + N_e = 0 (the force on the Earth is -F_moon by construction, so the total force is
    zero): every figure torque is balanced by the moment of its reaction force, to rounding, the Earth rigid
    or gyroscopic (its figure axis from l by the Oppolzer terms), all the interactions together and each
    alone.  Bound 64 eps of the largest part or of the largest gyroscopic term w x I w the torques are read
    from (a lone small interaction's torque, ~1e9 G-scaled, is read beside the Moon's ~1e13); measured up
    to 29 eps over 200 random states of each case."""
    system = figures_alone(figures, earth_rotator)
    for _ in range(8):
        y = random_state(system)
        force, n_m, n_e, read_from = actions(system, y)
        parts = [np.cross(y[system.layout["moon.r"]], force), n_m, n_e]
        scale = max(read_from, *(np.linalg.norm(part) for part in parts))
        assert np.linalg.norm(sum(parts)) < 64 * EPS * scale


def test_each_interaction_is_on_alone_and_off_exactly():
    """The balance above is not 0 = 0: each interaction alone pulls and turns (the degree-2 torque on each
    body within the P91 bound 3 GM/r^3 (C - A)/2, §815), and with every figure off nothing does: the rhs is
    then the two free bodies' Euler equations and no acceleration."""
    from spinorbit.models.spin import euler_omega_dot

    for name in FIGURES:
        system = figures_alone((name,))
        force, n_m, n_e, _ = actions(system, random_state(system))
        assert np.linalg.norm(force) > 0 and np.linalg.norm(n_m) + np.linalg.norm(n_e) > 0, name
    moments_m, moments_e = (figures_alone().bodies[b].figure.moments for b in ("moon", "earth"))
    gm_e, gm_m = figures_alone().bodies["earth"].gm, figures_alone().bodies["moon"].gm
    system = figures_alone(("moon_figure",))
    y = random_state(system)
    r3 = np.linalg.norm(y[system.layout["moon.r"]]) ** 3
    bound = 1.5 * gm_e / r3 * (moments_m[2] - moments_m[0]) * (1 + 1e-12)
    assert np.linalg.norm(actions(system, y)[1]) <= bound
    system = figures_alone(("earth_figure",))
    y = random_state(system)
    r3 = np.linalg.norm(y[system.layout["moon.r"]]) ** 3
    bound = 1.5 * gm_m / r3 * (moments_e[2] - moments_e[0]) * (1 + 1e-12)
    assert np.linalg.norm(actions(system, y)[2]) <= bound
    system = figures_alone(())
    y = random_state(system)
    dy, layout = system.rhs(0.0, y, system.params), system.layout
    assert not dy[layout["moon.v"]].any()
    for name, moments in (("moon", moments_m), ("earth", moments_e)):
        omega = layout[f"{name}.omega"]
        assert np.array_equal(dy[omega], euler_omega_dot(moments, y[omega], np.zeros(3)))


def _minus_gradient(energy, r, step):
    return np.array([-(energy(r + step * e) - energy(r - step * e)) / (2 * step) for e in np.eye(3)])


ROT = matrix_from_quat(np.array([0.8, 0.1, -0.3, 0.5]))
R = np.array([[3.1e5, -2.2e5, 0.4e5]])


def test_point_mass_energy_gradient_is_the_force():
    """MacCullagh's energy -GM (r^2 tr I - 3 r.I r)/(2 r^5): minus its central-difference gradient is the
    §818 force (the finite difference good to ~1e-8 at a 10 km step)."""
    from spinorbit.bodies.moon import de421

    inertia = np.diag(de421().moments) + 1e-5 * np.array([[0, 1, 2], [1, 0, 3], [2, 3, 0]])
    gm = np.array([2.9e15])
    force = point_mass.force(ROT, inertia, R, gm)[0]
    numeric = _minus_gradient(lambda r: point_mass.energy(ROT, inertia, r[None], gm), R[0], 10.0)
    assert np.abs(force - numeric).max() < 1e-7 * np.abs(force).max()


@pytest.mark.parametrize("body", ["moon", "earth"])
def test_harmonics_energy_gradient_is_the_force(body):
    """The degree 3-4 field's energy -(GM_body R^2) (GM/R^2) W: minus its gradient is the interaction's force
    (the Moon's DE421 field; the Earth's J3, J4)."""
    figure = closed().bodies[body]
    field = figure.figure.field
    args = (figure.gm * field.radius_km ** 2, field.radius_km, field.c_nm, field.s_nm, field.n_min,
            field.n_max)
    gm = np.array([2.9e15])
    force = harmonics.force(ROT, R, gm, *args)[0]
    numeric = _minus_gradient(lambda r: harmonics.energy(ROT, r[None], gm, *args), R[0], 10.0)
    assert np.abs(force - numeric).max() < 1e-6 * np.abs(force).max()


# --- runs ---------------------------------------------------------------------------------

SPAN_D, STEP_D = 182.625, 0.05           # half a year; the Earth turns 0.3 rad a step


def started(figures=tuple(FIGURES)):
    """The closed system (rigid Moon and Earth) at J2000: DE421's Earth-Moon state and lunar orientation, the
    Earth's figure axis on the IAU pole spinning about it at the Earth rotation angle's rate."""
    from spinorbit.models.start import moon_de421, on_pole
    from spinorbit.orbits.kernel import open_ephemeris
    from spinorbit.references import erfa_pole

    system = closed(figures, earth_rotator=Rigid(), moon_core=False)
    pos, vel = open_ephemeris("de421", 0.0, 0.0).relative_states("moon", "earth", [0.0])
    earth_start = on_pole(system, "earth", 0.0, erfa_pole.cip_vector(0.0), earth.ERA_RATE_RAD_D, forced=False)
    return system.with_start(0.0, system.layout.pack({"moon.r": pos[0], "moon.v": vel[0], **moon_de421(0.0),
                                                      **earth_start}))


def drift(system, t, states):
    """Largest relative changes from the first state: |L|, the L vector (over |L|), the energy (over |E|)."""
    energy, big_l = system.invariants(states, t)
    norm = np.linalg.norm(big_l, axis=1)
    return {"L_norm_rel_drift": float(np.max(np.abs(norm / norm[0] - 1))),
            "L_vector_rel_drift": float(np.max(np.linalg.norm(big_l - big_l[0], axis=1)) / norm[0]),
            "energy_rel_drift": float(np.max(np.abs(energy / energy[0] - 1)))}


@pytest.fixture(scope="module")
def drifts():
    system, t = started(), np.linspace(0.0, SPAN_D, 101)
    return {h: drift(system, t, fixed_step(system.rhs, system.params, 0.0, system.y0, t, h))
            for h in (STEP_D, STEP_D / 2)}


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


def test_figures_off_is_the_kepler_orbit():
    """With every figure off the relative orbit is Kepler's with GM_e + GM_m: half a year (6.7 orbits,
    mean anomaly M = 42 rad) agrees to rounding.  The rounding walk of the energy, eps sqrt(N) over
    N = 3650 steps, moves the mean motion by 1.5 times that and the phase by M 1.5 eps sqrt(N) = 1.2e-12
    (measured 1.2e-12); bound 1e-11 relative (4 mm)."""
    system = started(())
    t = np.linspace(0.0, SPAN_D, 51)
    ys = fixed_step(system.rhs, system.params, 0.0, system.y0, t, STEP_D)
    r, v = system.layout["moon.r"], system.layout["moon.v"]
    exact = kepler(system.bodies["earth"].gm + system.bodies["moon"].gm, system.y0[r], system.y0[v], t)
    error = np.linalg.norm(ys[:, r] - exact, axis=1) / np.linalg.norm(exact, axis=1)
    assert error.max() < 1e-11


def test_the_stress_scene_reports_the_drifts_and_judges_only_a_decade():
    """scenarios/stress/coupled_conservation.toml over 20 days: the drifts it reports are at rounding
    (4 eps sqrt(N), N = 400 steps), and a span under 10 yr is not judged."""
    from pathlib import Path

    from spinorbit.edge.runner import run_scenario

    path = Path(__file__).parents[2] / "scenarios" / "stress" / "coupled_conservation.toml"
    summary = run_scenario(path, ['span.end="20 d"', "output.plots=false"]).summary
    for name in ("L_norm_rel_drift", "L_vector_rel_drift", "energy_rel_drift"):
        assert summary["comparison"][name] < 4 * EPS * math.sqrt(400)
    assert summary["comparison"]["passed"] is None and summary["verdict"]["result"] == "not-compared"


def test_the_invariants_hold_the_lunar_cores_angular_momentum():
    """The closed assembly as it comes (the Moon's fluid core, the gyroscopic Earth): System.invariants'
    angular momentum is mu r x v + R ((I - I_c) w_m + I_c w_c) + l (the core's own in it: Folkner et al.
    2014, eqs. 34-35, whose friction and pressure torques are internal), and it keeps that over a year at
    0.25 d to rounding (measured 5e-15 relative; the core's share, left out, moved it by 9e-11): bound
    4 eps sqrt(N), N = 1461 steps."""
    from spinorbit.bodies.moon import de421
    from spinorbit.models.start import earth_moon_de421
    from spinorbit.references.erfa_pole import cip_vector

    system = closed()
    y0 = system.layout.pack(earth_moon_de421(system, 0.0, cip_vector(0.0), earth.ERA_RATE_RAD_D))
    t = np.linspace(0.0, 365.25, 101)
    states = fixed_step(system.rhs, system.params, 0.0, y0, t, 0.25)
    _, big_l = system.invariants(states, t)
    moon, terra, parts = system.bodies["moon"], system.bodies["earth"], system.layout.split(states)
    flattening = de421().core_flattening
    core = de421().core_c_over_c * moon.figure.moments[2] * np.array([1 - flattening, 1 - flattening, 1])
    mu, mantle = terra.gm * moon.gm / (terra.gm + moon.gm), moon.figure.moments - core
    by_hand = [mu * np.cross(r, v) + matrix_from_quat(q) @ (mantle * w + core * w_c) + spin
               for r, v, q, w, w_c, spin in zip(*(parts[name] for name in (
                   "moon.r", "moon.v", "moon.q", "moon.omega", "moon.omega_core", "earth.spin")))]
    norm = np.linalg.norm(big_l[0])
    assert np.abs(big_l - by_hand).max() < 1e-14 * norm
    assert np.linalg.norm(big_l - big_l[0], axis=1).max() < 4 * EPS * math.sqrt(365.25 / 0.25) * norm
