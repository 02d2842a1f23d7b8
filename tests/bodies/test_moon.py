"""The lunar model and its DE421 references.

Decoding checks (the de421 arrays at JDEPOC reproduce the header's PHI, THT, PSI and
OMEGAX/Y/Z), the NAIF PCK route against the arrays, the degree-n torque against
Euler's closed form, and the libration scene against DE421 on spans that fit in CI.
"""
import numpy as np
import pytest

from spinorbit.analysis.librations import pole_and_longitude_difference
from spinorbit.base.errors import EphemerisRangeError
from spinorbit.base.rotations import omega_body_from_euler313_rates
from spinorbit.bodies.moon import de421
from spinorbit.references import moon_de421 as ref
from tests.units import arcsec, mas

C = de421()


def test_angles_at_epoch_equal_header():
    angles, _ = ref.librations(C.epoch_tdb_d)
    assert np.abs(angles[0] - C.angles0_rad).max() < 1e-12          # rad (1e-12 rad = 0.2 uas)


def test_body_rates_at_epoch_equal_header():
    angles, rates = ref.librations(C.epoch_tdb_d)
    omega = omega_body_from_euler313_rates(angles[0], rates[0])
    assert np.abs(omega - C.omega0_rad_d).max() < 1e-13 * np.linalg.norm(C.omega0_rad_d)


def test_moments_match_published():
    # DE421 header (LBET, LGAM, C22M): A, B, C = 0.3930197, 0.3931092, 0.3932677 M R^2; C/MR^2 = 4 C22/gamma = 0.393268
    assert np.allclose(C.moments, [0.3930197, 0.3931092, 0.3932677], rtol=0, atol=1e-7)
    assert C.c_mr2 == pytest.approx(4 * C.c22 / C.gamma, rel=1e-9)


def test_pck_agrees_with_arrays():
    start, end = ref.pck_span()
    t = np.linspace(start, end, 4001)
    pole, lon = pole_and_longitude_difference(ref.Orientation()(t)["icrf_to_body"], ref.pck_matrix(t))
    # measured: 0.007 mas pole, 0.013 mas longitude over 1900-2050
    assert np.abs(pole).max() < 0.05 * mas
    assert np.abs(lon).max() < 0.05 * mas


def test_reference_range_errors():
    start, end = ref.libration_span()
    with pytest.raises(EphemerisRangeError):
        ref.librations([start - 1.0])
    with pytest.raises(EphemerisRangeError):
        ref.pck_matrix([ref.pck_span()[1] + 1.0])


def test_core_state_carried_from_epoch():
    """DE421's core angular velocity carried to JDEPOC itself is the header's OMGCX/Y/Z."""
    from spinorbit.models.start import core_de421

    got = core_de421(C.epoch_tdb_d)
    assert np.abs(got - C.omega_core0_rad_d).max() < 1e-15


def test_spherical_core_carry_equals_linear_solution():
    """With f_c = 0 the core's equation under DE421's mantle (spinorbit.models.start.core_rhs) is linear,
    C_c dw_c/dt = -k_v (w_c - w_m) in inertial axes, and its RK4 carry (0.5-d steps, as core_de421 runs it)
    equals the exact solution e^{-k T} w_0 + int_0^T k e^{-k (T - s)} w_m(s) ds (k = k_v/C_c), the integral
    by the trapezoid over DE421's mantle rates every 1/16 d (its error (h^2/12) k w_m'' T ~ 1e-13; RK4's
    (h w)^4 k T |w_m - <w_m>| / 120 ~ 1e-11): bound 1e-9 of |w|."""
    from scipy.integrate import trapezoid

    from spinorbit.base.layout import Layout
    from spinorbit.bodies import de421_orientation
    from spinorbit.integrators import simulate
    from spinorbit.models.ode import Ode
    from spinorbit.models.start import core_rhs

    coefficients, (start, end) = de421_orientation.series(), de421_orientation.span()
    length = (end - start) / coefficients.shape[0]
    k, c_c, t0, span = 3e-4, 7e-4, 1000.0, 500.0
    w0 = np.array([-0.006, -0.001, 0.2294])
    ode = Ode(core_rhs, (coefficients, start, length, k * c_c, c_c, c_c), t0, c_c * w0,
              Layout([("core.momentum", 3, "vector", "units of C, inertial")]))
    got = simulate(ode, [t0 + span], "rk4", {"step": 0.5}, estimate_error=False)[0].y[-1] / c_c
    s = t0 + np.linspace(0.0, span, 8001)
    w_m = np.array([m.T @ omega for m, omega in (de421_orientation.mantle(si, coefficients, start, length)
                                                 for si in s)])
    weights = k * np.exp(-k * (t0 + span - s))[:, None]
    expected = np.exp(-k * span) * w0 + trapezoid(weights * w_m, s, axis=0)
    assert np.abs(got - expected).max() < 1e-9 * 0.23


@pytest.mark.parametrize("level", [1, 2, 3, 4])
def test_the_generated_rhs_is_the_lunar_model(level):
    """The Moon's System at each level, its generated rhs at DE421's state (rates moved off it) against the
    level's equations evaluated by hand from DE421's constants and the interactions' kernels: the torques of
    the level's bodies on the degree-2 figure (§815) and on the degree 3-4 field, the Earth's J2 on the
    figure (the IAU 1976 pole table of references.moon_de421, as DE421), the inertia distorted by the tide the
    Earth raised tau ago (its position from the orbit source, its velocity by central differences of 1e-3 d)
    and the spin, the mantle and fluid core (Folkner et al. 2014, §III); q' = q (0, w) / 2.  Bound 1e-13 of
    each slice's largest rate (at this state the Earth's J2 is 6e-6 of the torque, the planets' 4e-8)."""
    from spinorbit.base.rotations import matrix_from_quat, quat_rate
    from spinorbit.bodies.de421_header import header
    from spinorbit.models import distortion, spin
    from spinorbit.models.assemblies.moon import LEVELS, moon
    from spinorbit.models.interactions import figure_figure, harmonics, point_mass
    from spinorbit.models.spin import euler_omega_dot
    from spinorbit.models.start import moon_de421
    from spinorbit.orbits.sources import sample_orbits
    from spinorbit.references.moon_de421 import earth_pole

    t, spec = 1234.5, LEVELS[level]
    orbits = sample_orbits("de421", "moon", spec.bodies, t - 2.0, t + 2.0, 0.5)
    pole = earth_pole(t - 2.0, t + 2.0)
    start = moon_de421(t, spec.core)
    start["moon.omega"] = start["moon.omega"] * (1.0 + np.array([1e-3, -2e-3, 5e-4]))
    system = moon(level, orbits, earth_pole=pole, t0=t, start=start)
    got = system.rhs(t, system.y0, system.params)

    h = header()
    parts = system.layout.split(system.y0)
    q, w = parts["moon.q"], parts["moon.omega"]
    rot, scale = matrix_from_quat(q), C.gm_km3_d2 * C.radius_km ** 2
    gm = np.asarray(orbits.gm, dtype=float)
    gm_earth = gm[list(orbits.names).index("earth")]
    rows = orbits.kernel(t, orbits.data)
    inertia, inertia_rate = np.diag(C.moments * scale), np.zeros((3, 3))
    if spec.tides:
        row = list(orbits.names).index("earth")
        then = orbits.kernel(t - C.tau_d, orbits.data)[row]
        then_v = (orbits.kernel(t - C.tau_d + 1e-3, orbits.data)[row]
                  - orbits.kernel(t - C.tau_d - 1e-3, orbits.data)[row]) / 2e-3
        r_del, v_del = distortion.delayed_in_body(rot, w, then, then_v, C.tau_d)
        delta, inertia_rate = distortion.distortion(w, r_del, v_del, C.k2 * gm_earth * C.radius_km ** 5,
                                                    C.k2 * C.radius_km ** 5 / 3, 2 * np.pi / 27.321661)
        inertia = inertia + delta
    torque = point_mass.torque(rot, inertia, rows, gm)
    if "harmonics" in spec.terms:
        torque = torque + harmonics.torque(rot, rows, gm, scale, C.radius_km, np.ascontiguousarray(C.c_nm),
                                           np.ascontiguousarray(C.s_nm), 3, 4)
    if "earth_j2" in spec.terms:
        earth_pole_now = figure_figure.pole_at(t, *pole)
        earth_row = rows[list(orbits.names).index("earth")]
        torque = torque + figure_figure.figure_torque(inertia, rot.T @ earth_row, rot.T @ earth_pole_now,
                                                      gm_earth * h["J2E"] * h["RE"] ** 2)
    if spec.core:
        c = C.moments[2] * scale
        rates = spin.mantle_and_core_rates(w, parts["moon.omega_core"], inertia, inertia_rate, torque,
                                           C.core_c_over_c * c, C.core_flattening, C.kv_over_c_per_d * c)
    else:
        rates = (euler_omega_dot(C.moments * scale, w, torque),)
    expected = np.concatenate([quat_rate(q, w), *rates])
    for name in system.layout.names:
        part = system.layout[name]
        assert np.abs(got[part] - expected[part]).max() < 1e-13 * np.abs(expected[part]).max(), name


# --- the scene against DE421 on 5 years (2000-2005) ------------------------------------

def _run(level, years=5):
    from spinorbit.edge.runner import run_scenario

    return run_scenario("scenarios/moon_libration.toml",
                        [f"model.level={level}", 'span.start="2000-01-01T12:00:00"', f'span.end="{years} yr"',
                         "output.plots=false", "integrator.estimate_error=false"])


def test_level2_against_de421_5yr():
    # measured 2000-2005: pole 6.80", longitude 1.33" (targets over 1900-2050: 12" / 2")
    c = _run(2).summary["comparison"]
    assert c["pole_error_max_arcsec"] * arcsec < 8.0 * arcsec
    assert c["longitude_error_max_arcsec"] * arcsec < 1.6 * arcsec


def test_level3_against_de421_5yr():
    # measured 2000-2005: pole 1.35 mas, longitude 0.32 mas (1900-2050: 3.6 mas / 0.52 mas;
    # before the oblate core and the Earth's J2: 0.66" / 0.032" here, 1.33" / 0.061" over 150 yr)
    result = _run(3)
    c = result.summary["comparison"]
    assert c["pole_error_max_arcsec"] * arcsec < 3 * mas
    assert c["longitude_error_max_arcsec"] * arcsec < 1 * mas
    # the model's residual columns agree with the summary, and the angles with DE421
    table = result.table
    assert np.abs(table["longitude_error"].value).max() == pytest.approx(c["longitude_error_max_arcsec"])
    assert np.abs(table["theta_minus_de421"].value).max() < 1.0


def test_span_outside_source_raises():
    from spinorbit.edge.runner import run_scenario

    with pytest.raises(EphemerisRangeError):
        run_scenario("scenarios/moon_libration.toml", ['span.start="1850-01-01T00:00:00"', 'span.end="1 yr"'])


def test_bad_level_names_key():
    from spinorbit.base.errors import ScenarioError
    from spinorbit.edge.runner import run_scenario

    with pytest.raises(ScenarioError, match="model.level"):
        run_scenario("scenarios/moon_libration.toml", ["model.level=7", 'span.end="1900-02-01T00:00:00"'])
