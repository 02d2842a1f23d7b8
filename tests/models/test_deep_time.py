"""Deep time: the averaged spin equations against closed forms, the orbital solution against DE421 and against
itself (resume, refusal), and a short span of the scene against ERFA's long-term precession and La2004.

Tolerances: the RK8's floor for the closed forms; for the orbit, the physics the N-body lacks (DE421's
asteroids, the Moon as a body: measured 0.04" in the normal, 4e-8 in the eccentricity vector over 1900-2050);
for the scene, the targets of issue 24 at 2 kyr (ERFA) and La2004's own distance from La93 over 20 kyr.
"""
import math
from types import SimpleNamespace

import numpy as np
import pytest

from spinorbit.analysis.theory import SymmetricPrecession, precession_constant
from spinorbit.base.constants import ARCSEC, JULIAN_CENTURY_D
from spinorbit.base.errors import InputError, ScenarioError
from spinorbit.bodies.table import gm_km3_d2
from spinorbit.integrators.rk8 import fixed_step
from spinorbit.models import deep_time
from spinorbit.orbits import solution
from tests.units import arcsec, deg

AU_KM = 149597870.7
YEAR_D = 365.25
KYR_D = 365250.0


def fixed_orbit(normal=(0.0, 0.0, 1.0), e=0.0, samples=16):
    """A grid of an orbit that does not move: normal ``normal``, eccentricity ``e`` along x."""
    grid = np.zeros((samples, 6))
    grid[:, :3] = np.asarray(normal) / np.linalg.norm(normal)
    grid[:, 3] = e
    return grid


def params(grid, alpha=0.0, geodesic=0.0, beta=0.0, recession=0.0, spin_tide=0.0, tilt=0.0, h=KYR_D):
    c = np.zeros(10)
    c[deep_time.FIGURE] = 1.0                         # the Earth's: E_d ~ omega^2
    c[[deep_time.ALPHA0, deep_time.SOLAR0, deep_time.BETA0, deep_time.GEODESIC, deep_time.RECESSION,
       deep_time.SPIN_TIDE, deep_time.TILT]] = alpha, 1.0, beta, geodesic, recession, spin_tide, tilt
    return grid, -h * (len(grid) - 1) / 2, h, c


def precession(states):
    """Node longitude of s about z (unwrapped) and obliquity."""
    return np.unwrap(np.arctan2(states[:, 0], -states[:, 1])), np.arccos(states[:, 2])


def test_solar_precession_is_eulers_p96_rate():
    # A spinner of E_d = (C - A)/C about the Sun on a circle: Euler's P96 precession N cos n (sect. 846) with
    # the gyroscopic ratio cc/aa, N = (3/2) GM (aa - cc)/(eps cc s^3) (theory.SymmetricPrecession).
    ed, spin, eps = 3.27379448e-3, 2 * math.pi * 1.0027378, math.radians(23.44)
    alpha = deep_time.constant_from_ellipticity(ed, spin, AU_KM, 0.0) / (1 + deep_time.lunar_ratio(AU_KM))
    cc, aa = 1.0 - ed, 1.0
    big_n = precession_constant(gm_km3_d2("sun"), AU_KM, spin, aa, cc)
    euler = SymmetricPrecession(spin, math.sqrt(gm_km3_d2("sun") / AU_KM**3), big_n, eps, ratio=aa / cc)
    t = np.linspace(0.0, 50 * KYR_D, 51)
    states = fixed_step(deep_time.rhs, params(fixed_orbit(), alpha=alpha), 0.0,
                        deep_time.start_state([0.0, -math.sin(eps), math.cos(eps)]), t, 100 * YEAR_D)
    longitude, obliquity = precession(states)
    rate = np.polyfit(t, longitude, 1)[0]
    assert rate == pytest.approx(-euler.precession_rate, rel=1e-9)     # retrograde
    assert np.abs(obliquity - eps).max() < 1e-12


def test_precession_constant_of_a_circular_orbit_and_geodesic_precession():
    # alpha cos(eps) - Omega_g, retrograde about the orbit normal, for any normal; |s| = 1 kept.
    alpha, geodesic, eps = 1e-6, 3e-9, math.radians(40.0)
    normal = np.array([0.3, -0.2, 0.9]) / np.linalg.norm([0.3, -0.2, 0.9])
    u = np.cross(normal, [1.0, 0.0, 0.0])
    s0 = math.cos(eps) * normal + math.sin(eps) * u / np.linalg.norm(u)
    t = np.linspace(0.0, 2e5, 41)
    states = fixed_step(deep_time.rhs, params(fixed_orbit(normal), alpha=alpha, geodesic=geodesic), 0.0,
                        deep_time.start_state(s0), t, 500.0)
    s = states[:, :3]
    cos_eps = s @ normal
    angle = np.unwrap(np.arctan2(s @ np.cross(normal, u / np.linalg.norm(u)), s @ (u / np.linalg.norm(u))))
    assert np.polyfit(t, angle, 1)[0] == pytest.approx(-(alpha * math.cos(eps) - geodesic), rel=1e-9)
    assert np.abs(np.linalg.norm(s, axis=1) - 1).max() < 1e-13
    assert np.abs(cos_eps - math.cos(eps)).max() < 1e-13


def test_constant_from_rate_gives_the_rate_back():
    psi = 5038.481507 * ARCSEC / JULIAN_CENTURY_D
    eps = 84381.406 * ARCSEC
    geodesic = deep_time.geodesic_rate(AU_KM, 299792.458 * 86400)
    alpha = deep_time.constant_from_rate(psi, eps, geodesic)
    assert alpha * math.cos(eps) - geodesic == pytest.approx(psi, rel=1e-14)
    # the de Sitter precession of a heliocentric orbit: 1.92"/cy (IERS Conventions 2010, sect. 5.6.4)
    assert geodesic / ARCSEC * JULIAN_CENTURY_D == pytest.approx(1.919883, abs=2e-3)


def test_tides_today_recession_length_of_day_and_precession_acceleration():
    # Today's lunar recession (38.30 mm/yr, LLR), Lambeck's omega' = 51 n', and the tides' acceleration of the
    # precession in longitude, -235 uas/cy^2 in IAU 2006's budget (Capitaine et al. 2003, Table 3, tides (a),
    # (b)).
    grid = fixed_orbit(e=0.0167)
    p = deep_time.parameters(grid, -8 * KYR_D, KYR_D, 5494.0 * ARCSEC / JULIAN_CENTURY_D, 0.0167, AU_KM,
                             299792.458 * 86400, 2 * math.pi * 1.0027378)
    y0 = deep_time.start_state([0.0, -math.sin(0.409), math.cos(0.409)])
    dy = deep_time.rhs(0.0, y0, p)
    assert dy[3] * 384399.0 * YEAR_D * 1e6 == pytest.approx(38.30, rel=1e-12)          # mm/yr
    lod_ms_per_cy = -dy[4] * 86400e3 * JULIAN_CENTURY_D
    assert 2.2 < lod_ms_per_cy < 2.5                  # 2.3 ms/cy tidal (Stephenson & Morrison 1995)
    c = p[3]
    rate = lambda y: c[deep_time.ALPHA0] * y[4] * (c[deep_time.SOLAR0] + c[deep_time.BETA0] * y[3] ** -3) / (
        c[deep_time.SOLAR0] + c[deep_time.BETA0]) * math.cos(0.409)
    acceleration = (rate(y0 + dy * JULIAN_CENTURY_D) - rate(y0)) * JULIAN_CENTURY_D / ARCSEC * 1e6  # uas/cy2
    assert acceleration == pytest.approx(-235, rel=0.05)


def test_climate_angles_at_j2000_and_a_quarter_turn():
    eps = math.radians(23.44)
    s0, n0 = np.array([0.0, 0.0, 1.0]), np.array([0.0, -math.sin(eps), math.cos(eps)])
    perihelion = np.array([[math.cos(1.0), math.sin(1.0) * math.cos(eps), math.sin(1.0) * math.sin(eps)]])
    q = deep_time.climate_angles(s0, n0, 0.0167 * perihelion, s0, n0)
    assert q["obliquity"][0] == pytest.approx(eps, abs=1e-15)
    assert q["perihelion_longitude"][0] == pytest.approx(1.0, abs=1e-14)     # from the equinox (x)
    assert q["precession"][0] == pytest.approx(0.0, abs=1e-15)
    turn = math.radians(-30.0)             # the axis regressed 30 deg about n0: varpi_bar, psi grow by 30 deg
    rotate = np.array([[math.cos(turn), -math.sin(turn), 0], [math.sin(turn), math.cos(turn), 0], [0, 0, 1]])
    to_ecliptic = np.array([[1, 0, 0], [0, math.cos(eps), math.sin(eps)], [0, -math.sin(eps), math.cos(eps)]])
    s = to_ecliptic.T @ rotate @ to_ecliptic @ s0
    q = deep_time.climate_angles(s, n0, 0.0167 * perihelion, s0, n0)
    assert q["precession"][0] == pytest.approx(math.radians(30.0), abs=1e-14)
    assert q["perihelion_longitude"][0] == pytest.approx(1.0 + math.radians(30.0), abs=1e-14)


# --- the orbital solution ---------------------------------------------------------------------------------


def test_orbit_against_de421_over_its_span(tmp_path):
    # The EMB's heliocentric orbit 1900-2050 against DE421: measured 0.040" (normal) and 3.8e-8 (e vector,
    # 0.5" of varpi); the EMB as a point mass is off by 5.4e-7 (6.7").  DE421's asteroids are missing here.
    from spinorbit.orbits.kernel import JPLKernel

    orbit = solution.solve(solution.Settings(output_d=365.0), -99 * YEAR_D, 53 * YEAR_D,
                           path=tmp_path / "s.npz")
    inside = orbit.t_d < 53 * YEAR_D                       # DE421: 1899.6-2053.7
    t = orbit.t_d[inside]
    p, v = JPLKernel().relative_states("earth_moon_barycenter", "sun", t)
    h = np.cross(p, v)
    mu = sum(gm_km3_d2(b) for b in ("sun", "earth", "moon"))
    ecc = np.cross(v, h) / mu - p / np.linalg.norm(p, axis=1)[:, None]
    normal = h / np.linalg.norm(h, axis=1)[:, None]
    assert np.arccos(np.clip(np.sum(normal * orbit.normal[inside], axis=1), -1, 1)).max() < 0.1 * arcsec
    assert np.linalg.norm(ecc - orbit.eccentricity_vector[inside], axis=1).max() < 1e-7
    # Mars's, kept beside it (mars_deep_time): measured 0.0043" and 1.2e-7 (DE421's asteroids are missing)
    p, v = JPLKernel().relative_states("mars", "sun", t)
    h = np.cross(p, v)
    ecc = np.cross(v, h) / (gm_km3_d2("sun") + gm_km3_d2("mars")) - p / np.linalg.norm(p, axis=1)[:, None]
    mars = orbit.of("mars")
    normal = h / np.linalg.norm(h, axis=1)[:, None]
    assert np.arccos(np.clip(np.sum(normal * mars.normal[inside], axis=1), -1, 1)).max() < 0.05 * arcsec
    assert np.linalg.norm(ecc - mars.eccentricity_vector[inside], axis=1).max() < 5e-7


def test_orbit_extended_from_a_file_is_bit_identical_and_a_mismatching_file_is_refused(tmp_path):
    settings = solution.Settings(output_d=3650.0)
    solution.solve(settings, -1000 * YEAR_D, 0.0, path=tmp_path / "a.npz")
    extended = solution.solve(settings, -2000 * YEAR_D, 0.0, path=tmp_path / "a.npz")
    fresh = solution.solve(settings, -2000 * YEAR_D, 0.0, path=tmp_path / "b.npz")
    assert np.array_equal(extended.t_d, fresh.t_d)
    assert np.array_equal(extended.eccentricity_vector, fresh.eccentricity_vector)
    assert np.array_equal(extended.normal, fresh.normal)
    with pytest.raises(InputError, match="differs in step_d 5.0 .this run: 2.5.") as info:
        solution.solve(solution.Settings(step_d=2.5, output_d=3650.0), -1000 * YEAR_D, 0.0,
                       path=tmp_path / "a.npz")
    assert "\n" not in str(info.value)


def test_orbit_file_with_altered_arrays_is_refused(tmp_path):
    settings = solution.Settings(output_d=3650.0)
    solution.solve(settings, -100 * YEAR_D, 0.0, path=tmp_path / "a.npz")
    with np.load(tmp_path / "a.npz") as data:                          # new numbers beside the old hash
        arrays = {name: data[name] for name in data.files}
    arrays["mars_eccentricity_vector"][0, 0] += 1e-9
    with open(tmp_path / "a.npz", "wb") as f:
        np.savez(f, **arrays)
    with pytest.raises(InputError, match="do not match their hash"):
        solution.OrbitalSolution.load(tmp_path / "a.npz", settings.record())


def test_settings_refuse_what_the_integration_cannot_vouch_for():
    with pytest.raises(InputError, match="whole number of WHFast steps"):
        solution.Settings(output_d=36524.0).check()
    with pytest.raises(InputError, match="step"):
        solution.Settings(step_d=30.0).check()
    with pytest.raises(InputError, match="moon"):
        solution.Settings(moon="body").check()


# --- the scene ----------------------------------------------------------------------------------------


def run(tmp_path, *overrides):
    from spinorbit import run_scenario

    return run_scenario("scenarios/earth_deep_time.toml",
                        [f'orbit.file="{tmp_path / "orbit.npz"}"', 'span.end="-10 kyr"', *overrides])


def test_scene_over_10_kyr_against_erfa_and_la2004(tmp_path):
    pytest.importorskip("inso")
    summary = run(tmp_path).summary
    c = summary["comparison"]
    assert summary["verdict"]["result"] == "pass"
    assert c["erfa_obliquity_max_arcsec"] < 1.0                # issue 24: 1" over +-2 kyr (measured 0.74")
    assert c["erfa_equator_max_arcsec"] < 5.0                  # measured 1.28"
    # La2004 over 10 kyr: well inside its own distance from La93 (0.0005 deg, 6e-5 over 20 kyr)
    assert c["la2004_obliquity_max_deg_span"] < 0.001          # measured 0.00016 deg
    assert c["la2004_climatic_precession_vector_max_span"] < 2e-5
    assert c["la2004_minus_la93_obliquity_max_deg_span"] > 2 * c["la2004_obliquity_max_deg_span"]


def test_scene_without_inso_runs_and_says_not_compared(tmp_path, monkeypatch):
    from spinorbit.references import laskar

    monkeypatch.setattr(laskar, "available", lambda: "the inso package is not installed")
    summary = run(tmp_path, 'span.end="-3 kyr"').summary
    assert summary["comparison"]["la2004_obliquity_max_deg_span"] is None
    assert "inso" in summary["not_measured"]["comparison.la2004_obliquity_max_deg_span"]
    assert summary["comparison"]["erfa_obliquity_max_arcsec"] < 1.0


@pytest.mark.parametrize("override, key", [
    ('span.start="2001-01-01T00:00:00"', "span.start"),
    ('span.end="-101 Myr"', "span.end"),
    ("model.Td=2.5", "model.Td"),
    ("model.Ed=1.05", "model.Ed"),
    ('orbit.step="8 d"', "orbit.step"),
    ('orbit.output="36524 d"', "orbit.output"),
    ('integrator.step="2 kyr"', "integrator.step"),
    ('integrator.method="rk4"', "integrator.method"),
])
def test_scene_refuses_what_it_cannot_vouch_for_in_one_line(tmp_path, override, key):
    with pytest.raises(ScenarioError) as info:
        run(tmp_path, override)
    assert str(info.value).startswith(f"{key}:") and "\n" not in str(info.value)


def test_obliquity_at_j2000_is_iau_2006s_within_the_osculating_ecliptic(tmp_path):
    # The axis starts on IAU 2006's mean pole; the osculating ecliptic of DE421 sits 0.25" from the mean one.
    from spinorbit.starts import earth_deep_time as deep_time_model

    orbit = solution.solve(solution.Settings(output_d=3650.0), -100 * YEAR_D, 0.0, path=tmp_path / "s.npz")
    p = SimpleNamespace(model=SimpleNamespace(precession="iau2006_rate", tidal_tilt=True, Ed=1.0, Td=1.0),
                        orbit=SimpleNamespace(output=3650.0, moon="ring"))
    model = deep_time_model.spin_model(p, orbit)
    obliquity = model.description["obliquity_j2000_deg"] * deg
    assert obliquity == pytest.approx(84381.406 * arcsec, abs=0.5 * arcsec)
    assert model.description["psi_rate_j2000_arcsec_per_cy"] == pytest.approx(5038.481507, rel=1e-12)


def test_orbit_interrupted_half_way_is_kept_and_continued_bit_for_bit(tmp_path, monkeypatch):
    settings = solution.Settings(output_d=3650.0)
    advance, calls = solution._ReboundBranch.advance, []

    def interrupted(run):
        calls.append(1)
        if len(calls) == 60:
            raise KeyboardInterrupt
        return advance(run)

    monkeypatch.setattr(solution._ReboundBranch, "advance", interrupted)
    with pytest.raises(KeyboardInterrupt):
        solution.solve(settings, -1000 * YEAR_D, 0.0, path=tmp_path / "a.npz")
    kept = solution.OrbitalSolution.load(tmp_path / "a.npz", settings.record())
    assert kept.span == (-59 * 3650.0, 0.0)
    monkeypatch.setattr(solution._ReboundBranch, "advance", advance)
    continued = solution.solve(settings, -1000 * YEAR_D, 0.0, path=tmp_path / "a.npz")
    fresh = solution.solve(settings, -1000 * YEAR_D, 0.0, path=tmp_path / "b.npz")
    assert np.array_equal(continued.eccentricity_vector, fresh.eccentricity_vector)


def test_sweep_over_td_and_ed_computes_the_orbit_once(tmp_path, monkeypatch):
    from spinorbit.edge.sweep import run_sweep

    extend, calls = solution._extend, []
    monkeypatch.setattr(solution, "_extend", lambda *args: calls.append(1) or extend(*args))
    grid = {"model.Td": ["0", "1"], "model.Ed": ["0.999", "1"]}
    records = run_sweep("scenarios/earth_deep_time.toml", grid,
                        tmp_path / "sweep", scheduler="synchronous",
                        base_overrides=[f'orbit.file="{tmp_path / "orbit.npz"}"', 'span.end="-5 kyr"',
                                        "output.plots=false"])
    assert [r["status"] for r in records] == ["ok"] * 4
    assert len(calls) == 1
    # Ed moves today's precession away from the observed one: ERFA's equator tells (Td barely, over 2 kyr)
    equator = {tuple(r["overrides"][-2:]): r["erfa_equator_max_arcsec"] for r in records}
    assert equator[("model.Td=1", "model.Ed=0.999")] > 10 * equator[("model.Td=1", "model.Ed=1")]
