"""Orbit sources: DE421 readers vs skyfield, the interpolant's error bound, Kepler vs a numerical two-body run."""
import math

import numpy as np
import pytest

from spinorbit.base.errors import EphemerisRangeError, InputError
from spinorbit.orbits import kernel as kernel_module
from spinorbit.orbits.analytic import CircularOrbits, KeplerOrbit
from spinorbit.orbits.interpolant import HermiteOrbits, grid
from spinorbit.orbits.kernel import DE421Arrays, JPLKernel, open_ephemeris
from spinorbit.orbits.sources import sample_orbits
from tests.units import arcsec, mas

EPOCHS = np.array([-36000.0, -10000.5, 0.0, 1234.567, 19000.25])   # TDB days from J2000, 1901-2052
PAIRS = [("moon", "earth"), ("earth", "moon"), ("sun", "moon"), ("jupiter", "earth"), ("venus", "sun"),
         ("earth", "solar_system_barycenter")]


def angle(a, b):
    """Angle between rows of a and b, rad."""
    return np.arctan2(np.linalg.norm(np.cross(a, b), axis=-1), (a * b).sum(-1))


@pytest.fixture(scope="module")
def de421():
    return JPLKernel()


@pytest.mark.parametrize("target, center", PAIRS)
def test_de421_matches_skyfield(de421, target, center):
    from skyfield.api import load, load_file

    eph = load_file(str(kernel_module.kernel_path("de421")))
    ts = load.timescale(builtin=True)
    names = {"earth": "earth", "moon": "moon", "sun": "sun", "jupiter": "jupiter barycenter",
             "venus": "venus"}
    vector = eph[names[target]] if center == "solar_system_barycenter" else eph[names[target]] - eph[names[center]]
    state = vector.at(ts.tdb_jd(2451545.0, EPOCHS))
    pos, vel = de421.relative_states(target, center, EPOCHS)
    assert np.abs(pos - state.position.km.T).max() < 1e-6                     # km
    assert np.abs(vel - state.velocity.km_per_s.T * 86400).max() < 1e-7       # km/day
    assert angle(pos, state.position.km.T).max() < 1e-3 * mas


@pytest.mark.parametrize("target, center", PAIRS)
def test_de421_arrays_match_bsp(de421, target, center):
    arrays = DE421Arrays()
    pos, vel = de421.relative_states(target, center, EPOCHS)
    pos2, vel2 = arrays.relative_states(target, center, EPOCHS)
    # the same Chebyshev series: equal to rounding (measured 3e-5 km on 1.3e8 km, Sun from Moon)
    assert (np.linalg.norm(pos - pos2, axis=1) / np.linalg.norm(pos, axis=1)).max() < 1e-12
    assert (np.linalg.norm(vel - vel2, axis=1) / np.linalg.norm(vel, axis=1)).max() < 1e-11
    assert angle(pos, pos2).max() < 1e-3 * mas


def test_de421_beyond_the_bsp_uses_the_arrays():
    assert open_ephemeris("de421", 0.0, 30000.0).span[1] == pytest.approx(73079.5)  # 2200-01
    with pytest.raises(EphemerisRangeError, match="covers 1899-07-29 to 2200-02-01 TDB .*; asked for 2000-01-01 to "
                                                  "2219-01-13.*'de440'.*'rebound'"):
        open_ephemeris("de421", 0.0, 80000.0)


def test_out_of_span_raises_with_the_span(de421):
    with pytest.raises(EphemerisRangeError,
                       match="covers 1899-07-29 00:00 to 2053-10-09 00:00 TDB; asked for 2053-10-09 12:00"):
        de421.relative_states("moon", "earth", [19640.0])
    orbits = sample_orbits("de421", "moon", ("earth",), 0.0, 10.0)
    with pytest.raises(EphemerisRangeError, match="covers 2000-01-01 to 2000-01-11 TDB; asked for 2000-01-12"):
        orbits.positions([10.5])
    inside, outside = orbits.kernel(10.0, orbits.data), orbits.kernel(10.0 + 1e-9, orbits.data)
    assert np.all(np.isfinite(inside)) and np.all(np.isnan(outside))      # never clamped
    assert np.all(np.isnan(orbits.kernel(-1e-9, orbits.data)))


def test_unknown_source_and_body_name_the_choices(de421):
    with pytest.raises(InputError, match="^source: got .de999."):
        kernel_module.kernel_path("de999")
    with pytest.raises(InputError, match="^body: got .vulcan."):
        de421.relative_states("vulcan", "earth", [0.0])


def test_a_bsp_dropped_into_ephemerides_is_found_by_name(tmp_path, monkeypatch):
    (tmp_path / "mykernel.bsp").symlink_to(kernel_module.kernel_path("de421"))
    monkeypatch.setattr(kernel_module, "EPHEMERIDES_DIR", tmp_path)
    orbits = sample_orbits("mykernel", "earth", ("moon",), 0.0, 2.0)
    assert orbits.source == "mykernel"
    expected = JPLKernel().relative_states("moon", "earth", [1.0])[0]
    assert np.abs(orbits.positions([1.0])[0] - expected).max() < 0.01    # km


def test_hermite_error_on_a_circle_is_the_h6_bound():
    """Quintic Hermite error at mid-points = r (omega h)^6 / 46080 (6th-derivative remainder)."""
    radius, rate, step = 384400.0, 2 * math.pi / 27.32, 0.25
    circle = CircularOrbits(("earth",), [1.0], [radius], [rate], inclination=[0.3])
    t = grid(0.0, 60.0, step)
    pos = circle.positions(t).transpose(1, 0, 2)
    vel = np.array([np.cross([0, -math.sin(0.3), math.cos(0.3)], p) * rate for p in pos[0]])[None]
    bound = radius * (rate * step) ** 6 / 46080                     # km (3.0e-7 km)
    exact = HermiteOrbits(("earth",), [1.0], 0.0, step, pos, vel, accelerations=-rate**2 * pos)
    assert 0.99 * bound < exact.measure_error(circle.positions)[0] < 1.01 * bound     # measured 1.0004
    # accelerations differenced from the velocities: one-sided stencils at the ends cost a little
    derived = HermiteOrbits(("earth",), [1.0], 0.0, step, pos, vel)
    assert derived.measure_error(circle.positions)[0] < 1.5 * bound                   # measured 1.28


def test_derived_accelerations_match_the_chebyshev_second_derivative():
    """Accelerations differenced from DE421 velocity samples vs the series' own 2nd derivative (numpy chebder)."""
    from jplephem.spk import SPK
    from numpy.polynomial import chebyshev

    from spinorbit.base.constants import J2000_JD

    orbits = sample_orbits("de421", "moon", ("earth",), 0.0, 365.25, measure=False)
    spk = SPK.open(str(kernel_module.kernel_path("de421")))

    def acceleration(segment, t):
        start, length, coef = segment.load_array()
        index, offset = np.divmod(t + J2000_JD - start, length)
        c = coef[:, index.astype(int)].transpose(2, 0, 1)
        return chebyshev.chebval(2 * offset / length - 1, chebyshev.chebder(c, 2), tensor=False).T \
            * (2 / length) ** 2

    t = orbits.span[0] + orbits.step * np.arange(orbits.data[1].shape[1])
    truth = acceleration(spk[3, 399], t) - acceleration(spk[3, 301], t)       # Earth from the Moon
    rel = np.linalg.norm(orbits.data[3][0] - truth, axis=1) / np.linalg.norm(truth, axis=1)
    assert rel.max() < 5e-8                    # measured 1.8e-8 (ends), 1.2e-8 inside


def test_de421_interpolation_error_is_within_the_stated_bound():
    """Moon-centred Earth and Sun at 0.25 d: |dr|/r < 1e-11 (torque error < 5e-11), measured 3.7e-12."""
    orbits = sample_orbits("de421", "moon", ("earth", "sun"), 0.0, 365.25)
    assert np.all(orbits.max_error_km < 5e-6)                 # km; measured 1.33e-6, 1.33e-6
    assert orbits.max_relative_error[0] < 1e-11               # measured 3.7e-12
    assert orbits.max_relative_error[1] < 3e-14               # measured 8.7e-15
    t = np.linspace(0.1, 365.0, 97)
    truth = JPLKernel().relative_states("earth", "moon", t)[0]
    assert angle(orbits.positions(t)[:, 0], truth).max() < 2e-6 * arcsec      # measured 3.9e-7"


def test_kepler_matches_a_numerical_two_body_run():
    from scipy.integrate import solve_ivp

    mu, a, e = 1.0e6, 1.0e4, 0.6
    orbit = KeplerOrbit(("p",), [mu], [a], [e], mean_anomaly=[0.7], periapsis=[1.1],
                        inclination=[0.4], node=[-0.5])
    period = 2 * math.pi / orbit.mean_motion[0]
    r0 = orbit.positions([0.0])[0, 0]
    h = 0.1                                     # 4th-order central difference for the velocity
    f = lambda dt: orbit.positions([dt])[0, 0]
    v0 = (8 * (f(h) - f(-h)) - (f(2 * h) - f(-2 * h))) / (12 * h)
    run = solve_ivp(lambda t, y: np.r_[y[3:], -mu * y[:3] / np.linalg.norm(y[:3]) ** 3],
                    (0, 3 * period), np.r_[r0, v0], method="DOP853", rtol=1e-13, atol=1e-9,
                    dense_output=True)
    t = np.linspace(0, 3 * period, 301)
    assert np.abs(orbit.positions(t)[:, 0] - run.sol(t)[:3].T).max() < 1e-8 * a      # km


def test_kepler_orientation_is_node_inclination_periapsis():
    from scipy.spatial.transform import Rotation

    a, e, node, incl, peri = 7.0, 0.3, 0.8, 0.5, -1.2
    orbit = KeplerOrbit(("p",), [1.0], [a], [e], periapsis=[peri], inclination=[incl], node=[node])
    rotation = Rotation.from_euler("ZXZ", [node, incl, peri])        # Rz(node) Rx(i) Rz(peri)
    assert np.abs(orbit.positions([0.0])[0, 0] - rotation.apply([a * (1 - e), 0, 0])).max() < 1e-14


def test_kepler_circle_is_the_circle():
    kepler = KeplerOrbit(("s",), [1.0], [2.0], [0.0], [0.3], mean_anomaly=[0.5], inclination=[0.2])
    circle = CircularOrbits(("s",), [1.0], [2.0], [0.3], phase=[0.5], inclination=[0.2])
    t = np.linspace(-50, 50, 41)
    assert np.abs(kepler.positions(t) - circle.positions(t)).max() < 1e-14


def test_kepler_rejects_hyperbolic_eccentricity():
    with pytest.raises(InputError, match="^e: got"):
        KeplerOrbit(("s",), [1.0], [1.0], [1.2])


@pytest.mark.parametrize("kind", ["kepler", "circular"])
def test_two_body_sources_pass_through_the_de421_state(de421, kind):
    orbits = sample_orbits(kind, "earth", ("moon",), 100.0, 200.0)
    truth = de421.relative_states("moon", "earth", [100.0])[0]
    assert np.abs(orbits.positions([100.0])[0] - truth).max() < 1e-6     # km
    # after a day the two-body orbit has left DE421 by the solar perturbation, < 0.5 %
    drift = np.linalg.norm(orbits.positions([101.0])[0] - de421.relative_states("moon", "earth", [101.0])[0])
    assert drift < 0.005 * np.linalg.norm(truth)


def test_each_source_says_what_it_covers_and_where_it_comes_from():
    """DE421 covers 1899-07-29 to 2200 (Folkner et al. 2008: the .bsp to 2053, the de421 package's arrays
    beyond), REBOUND any epoch, the analytic orbits read no ephemeris; the capabilities the scenes ask."""
    from spinorbit.orbits.sources import orbit_source

    de421, rebound, circular = orbit_source("de421"), orbit_source("rebound"), orbit_source("circular")
    first, last = de421.span()
    assert first == pytest.approx(-36680.5) and last == pytest.approx(73079.5)       # TDB days from J2000
    assert de421.covers(0.0, 30000.0) and not de421.covers(0.0, 80000.0)
    assert rebound.covers(-1e6, 1e6) and "DE421" in rebound.provenance()["name"]
    assert "2200" in de421.provenance()["span"] and circular.provenance() is None
    assert de421.lunar_angles and not rebound.lunar_angles and not orbit_source("de440").lunar_angles
    assert circular.circular and circular.analytic and not orbit_source("kepler").circular
    with pytest.raises(InputError, match="^source: got .circular."):
        circular.barycentric(("sun",), 0.0, 10.0)


def test_no_orbit_source_is_compared_by_name_outside_the_orbits():
    """Scenes, provenance and the API ask the source object (orbit_source(name).circular, .lunar_angles,
    .covers, .provenance()), never `source == "de421"`: a new source is one class in spinorbit.orbits."""
    import ast
    from pathlib import Path

    names = {"de421", "de440", "circular", "kepler", "rebound"}
    package = Path(__file__).parents[1] / "spinorbit"
    found = []
    for path in package.rglob("*.py"):
        if "orbits" in path.relative_to(package).parts:
            continue
        text = path.read_text()
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.Compare):
                sides = [node.left, *node.comparators]
                constants = [s for s in sides if isinstance(s, ast.Constant) and s.value in names]
                constants += [e for s in sides if isinstance(s, (ast.Tuple, ast.List, ast.Set)) for e in s.elts
                              if isinstance(e, ast.Constant) and e.value in names]
                if constants and ("source" in ast.get_source_segment(text, node)
                                  or "ephemeris" in ast.get_source_segment(text, node)):
                    found.append(f"{path.relative_to(package)}:{node.lineno}")
    assert not found, found


def test_a_source_is_made_from_a_name_only_where_a_name_comes_in():
    """orbit_source(name) (and the entry points taking a name) is called where a string comes in: loading
    (params.source_key), the API's arguments (api, and solutions.tables, which answers the API with them), a
    stored solution's provenance (solutions.tracks); past loading, code holds the OrbitSource."""
    import ast
    from pathlib import Path

    package = Path(__file__).parents[1] / "spinorbit"
    found = sorted(f"{path.relative_to(package)}:{node.lineno}" for path in package.rglob("*.py")
                   if "orbits" not in path.relative_to(package).parts
                   and path.stem not in ("params", "api", "tables", "tracks")
                   for node in ast.walk(ast.parse(path.read_text()))
                   if isinstance(node, ast.Call) and isinstance(node.func, ast.Name)
                   and node.func.id in ("orbit_source", "sample_orbits", "barycentric", "ephemeris_identity"))
    assert not found, found
