"""The Earth-Moon system in the solar system (spinorbit.models.assemblies.earth_moon.solar_system): its
generated rhs against its physics written out, the Moon's orbit against DE421, the closed system's angular
momentum, and the scene.

Run times: one compile of the rhs (~30 s cold, cached after), then 2 yr of integration (~0.5 s each).
"""
import copy
from pathlib import Path

import numpy as np
import pytest

from spinorbit.base.rotations import matrix_from_quat
from spinorbit.bodies import earth
from spinorbit.integrators.rk8 import fixed_step
from spinorbit.models.assemblies.earth_moon import EXTERNAL, solar_system
from spinorbit.models.start import earth_moon_de421
from spinorbit.orbits.kernel import open_ephemeris
from spinorbit.orbits.sources import barycentric
from spinorbit.references.erfa_pole import cip_vector
from tests.units import arcsec

T0 = -18262.5                       # 1950-01-01 TDB, days from J2000
SPAN_D = 730.5
STEP_D = 0.5
EPS = np.finfo(float).eps
# DE421's equations: the switches the comparison with DE421 runs (the planets' torques on the Moon's figure
# and the Sun's on the Earth's J3, J4 are not in DE421)
DE421_SWITCHES = ("relativity", "earth_tides", "moon_distortion", "geodesic", "planets")


@pytest.fixture(scope="module")
def external():
    return barycentric("de421", EXTERNAL, T0 - 1.0, T0 + SPAN_D + 1.0)


def massless(external):
    """The same orbit source with every GM zero: the pair alone (no Sun, planets nor solar tide)."""
    out = copy.copy(external)
    out.gm = np.zeros_like(external.gm)
    return out


def run(external, switches=DE421_SWITCHES, step=STEP_D, span=SPAN_D):
    """(t, states, system) over ``span`` days from DE421's state at T0."""
    system = solar_system(external, switches, T0)
    y0 = system.layout.pack(earth_moon_de421(system, T0, cip_vector(T0), earth.ERA_RATE_RAD_D))
    t = np.linspace(T0, T0 + span, int(span * 2 / 3) + 1)
    return t, fixed_step(system.rhs, system.params, T0, y0, t, step), system


def direction_and_range(t, states, system):
    de421, _ = open_ephemeris("de421", t[0], t[-1]).relative_states("moon", "earth", t)
    r = states[:, system.layout["moon.r"]]
    angle = np.arctan2(np.linalg.norm(np.cross(r, de421), axis=1), np.sum(r * de421, axis=1))
    return angle.max(), np.abs(np.linalg.norm(r, axis=1) - np.linalg.norm(de421, axis=1)).max()


def direct_rhs(external, t, y):
    """dy/dt of the solar-system Earth-Moon model at (t, y) written out from DE421's constants and the
    interactions' kernels (the state: moon.r, .v, .q, .omega, .omega_core, earth.spin; every switch on).

    Orbit: Newton (the pair's monopole, each other mass's pull on the Moon minus its pull on the Earth, the
    two about DE421's barycentre by their mass shares) + EIH + every figure's force on the two centres
    (F_moon / m_m - F_earth / m_e) + the Earth's tides.  Figures: the Moon's degree 2-4 under the Earth, the
    Sun and the planets; the Earth's degree 2 and J3, J4 under the Moon and the Sun; the Earth's J2 on the
    Moon's degree 2 with its reaction on the Earth; each pull's reaction on its figure (§818).  The Moon:
    DE421's mantle and fluid core with its inertia distorted by the tide the Earth raised tau ago (the Earth
    then from the orbit's point-mass acceleration and two-body jerk); the Earth: gyroscopic, its figure axis
    from l by the first-order Oppolzer term of the Moon's and the Sun's tidal tensor, its spin turned by the
    torques, the tides' reaction and the geodesic precession Omega x l, Omega = 3/2 GM_sun/(c^2 |x|^3) x x w.
    Returns (dy/dt, the Keplerian part of the orbit's acceleration)."""
    from spinorbit.base.constants import DAY_S
    from spinorbit.base.rotations import quat_rate
    from spinorbit.bodies.de421_header import header
    from spinorbit.bodies.moon import de421
    from spinorbit.bodies.table import gm_km3_d2
    from spinorbit.models import distortion, gyroscopic, spin
    from spinorbit.models.assemblies.earth_moon import PLANETS
    from spinorbit.models.interactions import figure_figure, harmonics, point_mass, relativity, tides
    from spinorbit.orbits.interpolant import hermite_states

    h, moon = header(), de421()
    names = list(external.names)
    gm = {name: gm_km3_d2(name) for name in ["earth", "moon", *names] if not name.endswith("barycenter")}
    r, v, q, w, w_c, l_spin = np.split(y, [3, 6, 10, 13, 16])
    pos, vel = hermite_states(t, external.data)
    share = gm["moon"] / (gm["earth"] + gm["moon"])
    bary = names.index("earth_moon_barycenter")
    x = {name: pos[k] for k, name in enumerate(names)} | {"earth": pos[bary] - share * r,
                                                         "moon": pos[bary] + (1.0 - share) * r}
    u = {name: vel[k] for k, name in enumerate(names)} | {"earth": vel[bary] - share * v,
                                                         "moon": vel[bary] + (1.0 - share) * v}
    masses = [name for name in names if name in gm]

    def seen(a, b):              # body b from body a; the pair from each other exactly +-r
        return {("earth", "moon"): r, ("moon", "earth"): -r}.get((a, b), x[b] - x[a])

    acc = -(gm["earth"] + gm["moon"]) * r / np.linalg.norm(r) ** 3
    for name in masses:
        acc += gm[name] * (seen("moon", name) / np.linalg.norm(seen("moon", name)) ** 3
                           - seen("earth", name) / np.linalg.norm(seen("earth", name)) ** 3)
    c_light = h["CLIGHT"] * DAY_S
    bodies = [*masses, "earth", "moon"]
    eih = relativity.accelerations(np.array([x[b] for b in bodies]), np.array([u[b] for b in bodies]),
                                   np.array([gm[b] for b in bodies]), c_light, np.array([len(bodies) - 2,
                                                                                        len(bodies) - 1]))[1]
    acc += eih[1] - eih[0]

    scale = gm["moon"] * moon.radius_km ** 2
    moments_m, rot_m = moon.moments * scale, matrix_from_quat(q)
    then, then_v = distortion.taylor_back(r, v, acc, gm["earth"] + gm["moon"], moon.tau_d)
    r_del, v_del = distortion.delayed_in_body(rot_m, w, -then, -then_v, moon.tau_d)
    delta, inertia_rate = distortion.distortion(w, r_del, v_del, moon.k2 * gm["earth"] * moon.radius_km ** 5,
                                                moon.k2 * moon.radius_km ** 5 / 3, 2 * np.pi / 27.321661)
    inertia_m = np.diag(moments_m) + delta
    c_minus_a = h["J2E"] * gm["earth"] * h["RE"] ** 2
    c_e = c_minus_a / earth.H_D
    tensor = gyroscopic.tidal_tensor(np.array([r, seen("earth", "sun")]), np.array([gm["moon"], gm["sun"]]))
    rot_e = gyroscopic.frame_from_axis(gyroscopic.figure_axis(l_spin, tensor, c_e - c_minus_a, c_minus_a))
    inertia_e = np.diag([c_e - c_minus_a, c_e - c_minus_a, c_e])
    c_nm_e = np.zeros((5, 5))
    c_nm_e[3, 0], c_nm_e[4, 0] = -h["J3E"], -earth.J4
    c_nm_m, s_nm_m = np.ascontiguousarray(moon.c_nm), np.ascontiguousarray(moon.s_nm)
    fields = {"moon": (scale, moon.radius_km, c_nm_m, s_nm_m, 3, 4),
              "earth": (gm["earth"] * h["RE"] ** 2, h["RE"], c_nm_e, np.zeros((5, 5)), 3, 4)}
    rot, inertia = {"moon": rot_m, "earth": rot_e}, {"moon": inertia_m, "earth": inertia_e}
    force, torque = {"earth": np.zeros(3), "moon": np.zeros(3)}, {"earth": np.zeros(3), "moon": np.zeros(3)}
    acting = {"moon": [("earth",), ("sun",), PLANETS], "earth": [("moon",), ("sun",)]}
    for figure, groups in acting.items():
        for attractors in groups:
            rows = np.array([seen(figure, b) for b in attractors])
            mu = np.array([gm[b] for b in attractors])
            degrees = [point_mass.force(rot[figure], inertia[figure], rows, mu)]
            if attractors != PLANETS:           # the planets act on the Moon's degree 2 alone (the assembly)
                degrees.append(harmonics.force(rot[figure], rows, mu, *fields[figure]))
            for pulls in degrees:
                for body, pull in zip(attractors, pulls):
                    if body in force:
                        force[body] += pull
                force[figure] -= pulls.sum(axis=0)
                torque[figure] -= np.cross(rows, pulls).sum(axis=0)
    on_moon, pull, reaction = figure_figure.with_pole(rot_m, inertia_m, -r, rot_e[:, 2], c_minus_a)
    torque["moon"] += rot_m @ on_moon
    force["earth"] += pull
    force["moon"] -= pull
    torque["earth"] += reaction
    acc += force["moon"] / gm["moon"] - force["earth"] / gm["earth"]

    love = earth.de421_tides()
    p = np.array([gm["earth"], gm["moon"], gm["sun"], h["RE"], *(love[m][0] for m in range(3)),
                  *(love[m][1] for m in range(3))])
    tide = tides.acceleration(r, v, seen("earth", "sun"), u["sun"] - u["earth"], l_spin / c_e, p)
    acc += tide
    torque["earth"] += tides.reaction(r, tide, p)
    helio, helio_v = x["earth"] - x["sun"], u["earth"] - u["sun"]
    geodesic = 1.5 * gm["sun"] / (c_light ** 2 * np.linalg.norm(helio) ** 3) * np.cross(helio, helio_v)

    core_c, friction = moon.core_c_over_c * moments_m[2], moon.kv_over_c_per_d * moments_m[2]
    on_mantle = rot_m.T @ torque["moon"]
    mantle_rate, core_rate = spin.mantle_and_core_rates(w, w_c, inertia_m, inertia_rate, on_mantle, core_c,
                                                        moon.core_flattening, friction)
    spin_rate = torque["earth"] + np.cross(geodesic, l_spin)
    dy = np.concatenate([v, acc, quat_rate(q, w), mantle_rate, core_rate, spin_rate])
    return dy, -(gm["earth"] + gm["moon"]) * r / np.linalg.norm(r) ** 3


def test_the_generated_rhs_is_the_models_physics(external):
    """The solar-system assembly with every switch on, its generated rhs at DE421's state at T0 + 100.3 d (the
    Moon's rates and the Earth's spin moved off it) against :func:`direct_rhs`: the orbit's acceleration apart
    from its Keplerian part to 1e-12 of that perturbation, the Moon's mantle and core rates and the Earth's
    spin rate to 1e-12 of their largest component (measured 8e-14, 2e-16, 0, 4e-16). Each switch is seen:
    without it the rhs moves by (measured) EIH 8e-6 and the Earth's tides 1.6e-9 of the orbit's perturbation,
    the Moon's distortion 2e-4 and the planets on its figure 1.3e-7 of its rates, the tides 1.1e-5, the
    geodesic precession 4e-4 and the Sun on J3, J4 8e-8 of the Earth's spin rate."""
    system = solar_system(external, t0=T0)
    t = T0 + 100.3
    start = earth_moon_de421(system, t, cip_vector(t), earth.ERA_RATE_RAD_D)
    start["moon.omega"] = start["moon.omega"] * (1.0 + np.array([1e-3, -2e-3, 5e-4]))
    start["earth.spin"] += 1e-6 * np.linalg.norm(start["earth.spin"]) * np.array([1.0, -2, 0.5])
    y = system.layout.pack(start)
    got = system.rhs(t, y, system.params)
    expected, kepler = direct_rhs(external, t, y)
    layout = system.layout
    assert np.array_equal(got[layout["moon.r"]], expected[layout["moon.r"]])
    velocity = layout["moon.v"]
    perturbation = np.abs(expected[velocity] - kepler).max()
    assert np.abs(got[velocity] - expected[velocity]).max() < 1e-12 * perturbation
    for name in ("moon.q", "moon.omega", "moon.omega_core", "earth.spin"):
        part = layout[name]
        assert np.abs(got[part] - expected[part]).max() < 1e-12 * np.abs(expected[part]).max(), name


def test_planets_off_with_an_orbit_source_that_carries_them_is_refused(external):
    """The "planets" switch puts Mercury to Pluto on the orbit; Newton takes every mass the orbit source
    carries, so the switch off with a source that carries them would leave them acting: refused, naming the
    switches (the scene samples a source without them)."""
    from spinorbit.base.errors import InputError

    with pytest.raises(InputError, match="^switches: got .*'planets' among them"):
        solar_system(external, ("relativity", "earth_tides"))


def test_the_moon_follows_de421_for_two_years(external):
    """From DE421's state, with DE421's equations and constants, the geocentric Moon stays on DE421's for
    2 yr to 0.005" and 2 m: the issue's aim (0.05" and 0.1 km over a century) taken linearly to 2 yr would
    allow 0.001", RK8's truncation at 0.5 d (0.0003" against 0.25 d over 2 yr) and DE421's own fit add
    their share, and 0.005" is still 15x below what leaving out the 1PN terms costs (next test)."""
    t, states, system = run(external)
    direction, distance = direction_and_range(t, states, system)
    assert direction < 0.005 * arcsec
    assert distance < 0.002


def test_relativity_is_what_the_moon_needs(external):
    """Without the EIH terms the Moon leaves DE421 by 6e-8 of the Earth's pull (5 U_sun/c^2 + v^2/c^2):
    > 0.03" in 2 yr, where the full model stays within 0.005"."""
    t, states, system = run(external, tuple(s for s in DE421_SWITCHES if s != "relativity"))
    assert direction_and_range(t, states, system)[0] > 0.03 * arcsec


def test_the_closed_system_keeps_its_angular_momentum(external):
    """No Sun or planets (their GMs zero), the Earth's tides on (their torque on the Earth is the orbit's
    reaction), the Moon rigid with its core: the total angular momentum mu r x v + R (I_m w_m + I_c w_c) + l
    stays within 1e-13 over 2 yr at 0.25 d (rounding walks as eps sqrt(N), N ~ 35000 stage evaluations: 4e-14;
    at 0.5 d RK8's truncation shows, 4e-13)."""
    from spinorbit.bodies.moon import de421

    _, states, system = run(massless(external), ("earth_tides",), step=0.25)
    moon, layout, flattening = system.bodies["moon"], system.layout, de421().core_flattening
    core = de421().core_c_over_c * moon.figure.moments[2] * np.array([1 - flattening, 1 - flattening, 1])
    gm_e, gm_m = system.bodies["earth"].gm, moon.gm
    mu = gm_e * gm_m / (gm_e + gm_m)
    parts = layout.split(states)
    mantle = moon.figure.moments - core
    total = np.array([mu * np.cross(r, v) + spin + matrix_from_quat(q) @ (mantle * w + core * w_c)
                      for r, v, q, w, w_c, spin in zip(*(parts[name] for name in (
                          "moon.r", "moon.v", "moon.q", "moon.omega", "moon.omega_core", "earth.spin")))])
    drift = np.linalg.norm(total - total[0], axis=1).max() / np.linalg.norm(total[0])
    assert drift < 1e-13


def test_rebound_externals_move_the_moon_no_more_than_their_departure_from_de421(external):
    """The Sun, planets and EMB from a REBOUND run (spinorbit.orbits.nbody, from DE421's state at T0 - 1 d)
    instead of DE421: over 60 days the heliocentric EMB departs from DE421's by dR (measured 1.1 m; REBOUND
    lacks DE421's asteroids, whose pull on the Earth, ~2e-5 km/d^2, moves it < 50 m in 60 d), and the Moon
    then feels the Sun's tide (scale T = GM_s r/R^3, 126 km/d^2) changed by ~3 T dR/R; a steady perturbing
    acceleration e displaces an orbit by at most ~3 e t^2 within a few months (its mean motion drifts): the
    coupled Moon may move by 9 T (dR/R) t^2 = 3 cm (measured 0.23 mm).  Wrong frames or a wrong EMB would
    move it by kilometres."""
    span = 60.0
    rebound = barycentric("rebound", EXTERNAL, T0 - 1.0, T0 + span + 1.0)
    t, ours, system = run(rebound, span=span)
    _, de421, _ = run(external, span=span)
    sun, emb = EXTERNAL.index("sun"), EXTERNAL.index("earth_moon_barycenter")
    sun_to_emb = [orbits.positions(t)[:, emb] - orbits.positions(t)[:, sun] for orbits in (rebound, external)]
    departure = np.linalg.norm(sun_to_emb[0] - sun_to_emb[1], axis=1).max()
    assert departure < 0.05                                       # km
    r = system.layout["moon.r"]
    distance, moon = np.linalg.norm(sun_to_emb[1], axis=1).min(), np.linalg.norm(de421[:, r], axis=1).max()
    tide = external.gm[sun] * moon / distance ** 3
    bound = 9.0 * tide * departure / distance * span ** 2         # km
    assert np.linalg.norm(ours[:, r] - de421[:, r], axis=1).max() < bound


def test_the_scene_writes_the_moon_and_judges_it():
    """scenarios/earth_moon_coupled.toml over 60 days: the geocentric Moon and the angles in the table, the
    four DE421 checks judged; asking for the tidal acceleration on a short span is not judged."""
    from spinorbit.edge.runner import run_scenario

    path = Path(__file__).parents[3] / "scenarios" / "earth_moon_coupled.toml"
    result = run_scenario(path, ['span.end="1950-03-02T00:00:00"', "compare.tides_off=true",
                                 "output.plots=false"])
    for column in ("moon_geocentric_x", "phi", "theta", "psi", "earth_axis_z", "pole_error"):
        assert column in result.table.colnames
    checks = {c["label"]: c["result"] for c in result.summary["verdict"]["checks"]}
    assert checks["Moon direction"] == "pass" and checks["lunar pole"] == "pass"
    assert checks["n_dot"] == "not-compared"
