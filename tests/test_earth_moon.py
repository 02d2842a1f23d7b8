"""The Earth-Moon system in the solar system (spinorbit.earth_moon): the Moon's orbit against DE421, the
closed system's angular momentum, and the scene.

Run times: one compile of the rhs (~30 s cold, cached after), then 2 yr of integration (~0.5 s each).
"""
from pathlib import Path

import numpy as np
import pytest

from spinorbit import earth_moon
from spinorbit.bodies import earth
from spinorbit.earth_moon_vs_de421 import start_state
from spinorbit.integrators.rk8 import fixed_step
from spinorbit.orbits.kernel import open_ephemeris
from spinorbit.references.erfa_pole import cip_vector
from spinorbit.rotations import matrix_from_quat
from tests.units import arcsec

T0 = -18262.5                       # 1950-01-01 TDB, days from J2000
SPAN_D = 730.5
STEP_D = 0.5
EPS = np.finfo(float).eps


@pytest.fixture(scope="module")
def external():
    return earth_moon.sample_external(T0 - 1.0, T0 + SPAN_D + 1.0)


def run(external, switches=earth_moon.SWITCHES, closed=False, step=STEP_D, span=SPAN_D):
    """(t, states) over ``span`` days from DE421's state at T0; ``closed``: no Sun, planets nor solar tide."""
    p = list(earth_moon.parameters(external.data, switches))
    if closed:
        p[1] = np.zeros_like(p[1])
        tides = p[5].copy()
        tides[2] = 0.0                          # GM of the Sun in the tide parameters
        p[5] = tides
    p = tuple(p)
    y0 = start_state(T0, cip_vector(T0), earth.ERA_RATE_RAD_D, p)
    t = np.linspace(T0, T0 + span, int(span * 2 / 3) + 1)
    return t, fixed_step(earth_moon.rhs, p, T0, y0, t, step), p


def direction_and_range(t, states):
    de421, _ = open_ephemeris("de421", t[0], t[-1]).relative_states("moon", "earth", t)
    r = states[:, :3]
    angle = np.arctan2(np.linalg.norm(np.cross(r, de421), axis=1), np.sum(r * de421, axis=1))
    return angle.max(), np.abs(np.linalg.norm(r, axis=1) - np.linalg.norm(de421, axis=1)).max()


def test_the_moon_follows_de421_for_two_years(external):
    """From DE421's state, with DE421's equations and constants, the geocentric Moon stays on DE421's for
    2 yr to 0.005" and 2 m: the issue's aim (0.05" and 0.1 km over a century) taken linearly to 2 yr would
    allow 0.001", RK8's truncation at 0.5 d (0.0003" against 0.25 d over 2 yr) and DE421's own fit add
    their share, and 0.005" is still 15x below what leaving out the 1PN terms costs (next test)."""
    t, states, _ = run(external)
    direction, distance = direction_and_range(t, states)
    assert direction < 0.005 * arcsec
    assert distance < 0.002


def test_relativity_is_what_the_moon_needs(external):
    """Without the EIH terms the Moon leaves DE421 by 6e-8 of the Earth's pull (5 U_sun/c^2 + v^2/c^2):
    > 0.03" in 2 yr, where the full model stays within 0.005"."""
    t, states, _ = run(external, tuple(s for s in earth_moon.SWITCHES if s != "relativity"))
    assert direction_and_range(t, states)[0] > 0.03 * arcsec


def test_the_closed_system_keeps_its_angular_momentum(external):
    """No Sun or planets, the Earth's tides on (their torque on the Earth is the orbit's reaction), the
    Moon rigid with its core: the total angular momentum mu r x v + R (I_m w_m + I_c w_c) + l stays within
    1e-13 over 2 yr at 0.25 d (rounding walks as eps sqrt(N), N ~ 35000 stage evaluations: 4e-14; at 0.5 d
    RK8's truncation shows, 4e-13)."""
    from spinorbit.moon import C_CORE, F_CORE

    t, states, p = run(external, ("earth_tides",), closed=True, step=0.25)
    consts, moments, gm_r2 = p[3]
    gm = p[2][0]
    mu = gm[0] * gm[1] / (gm[0] + gm[1])
    core = consts[C_CORE] * np.array([1.0 - consts[F_CORE], 1.0 - consts[F_CORE], 1.0])
    total = np.array([mu * np.cross(y[0:3], y[3:6]) + y[16:19]
                      + gm_r2 * matrix_from_quat(y[6:10]) @ ((moments - core) * y[10:13] + core * y[13:16])
                      for y in states])
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
    rebound = earth_moon.sample_external(T0 - 1.0, T0 + span + 1.0, source="rebound")
    t, ours, p = run(rebound, span=span)
    _, de421, _ = run(external, span=span)
    sun_to_emb = [orbits.positions(t)[:, earth_moon.EMB] - orbits.positions(t)[:, earth_moon.SUN]
                  for orbits in (rebound, external)]
    departure = np.linalg.norm(sun_to_emb[0] - sun_to_emb[1], axis=1).max()
    assert departure < 0.05                                       # km
    distance, moon = np.linalg.norm(sun_to_emb[1], axis=1).min(), np.linalg.norm(de421[:, :3], axis=1).max()
    tide = p[1][earth_moon.SUN] * moon / distance ** 3
    bound = 9.0 * tide * departure / distance * span ** 2         # km
    assert np.linalg.norm(ours[:, :3] - de421[:, :3], axis=1).max() < bound


def test_the_scene_writes_the_moon_and_judges_it():
    """scenarios/earth_moon_coupled.toml over 60 days: the geocentric Moon and the angles in the table, the
    four DE421 checks judged; asking for the tidal acceleration on a short span is not judged."""
    from spinorbit.results import run_scenario

    path = Path(__file__).parents[1] / "scenarios" / "earth_moon_coupled.toml"
    result = run_scenario(path, ['span.end="1950-03-02T00:00:00"', "compare.tides_off=true",
                                 "output.plots=false"])
    for column in ("moon_geocentric_x", "phi", "theta", "psi", "earth_axis_z", "pole_error"):
        assert column in result.table.colnames
    checks = {c["label"]: c["result"] for c in result.summary["verdict"]["checks"]}
    assert checks["Moon direction"] == "pass" and checks["lunar pole"] == "pass"
    assert checks["n_dot"] == "not-compared"
