"""The seeds' closed forms (spinorbit.analysis.theory) against published numbers and numerical integration."""
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from spinorbit.analysis import theory
from spinorbit.base.errors import PhysicsError, ResonanceError
from spinorbit.base.rotations import quat_angle
from spinorbit.integrators import simulate
from spinorbit.models.assemblies.idealised import free_body
from spinorbit.models.interactions import point_mass
from spinorbit.models.spin import euler_omega_dot

HLW_MOMENTS = np.array([2 / 3, 1.0, 2.0])                         # (2, 1, 2/3) in A <= B <= C order
HLW_OMEGA0 = np.array([math.sin(1.1), 0.0, math.cos(1.1)]) / HLW_MOMENTS
Q0 = np.array([0.3, 0.5, -0.2, 0.7]) / np.linalg.norm([0.3, 0.5, -0.2, 0.7])


def point_mass_torque(moments, r_body, gm):
    """Euler's P91 torque (§815) of one mass at r (body axes) through the point-mass interaction's kernel."""
    return point_mass.torque(np.eye(3), np.diag(moments), np.atleast_2d(r_body), np.array([gm]))


def _integrated(moments, omega0, q0, t):
    system = free_body(np.asarray(moments, float), np.asarray(q0, float), np.asarray(omega0, float))
    return simulate(system, t, "dop853", {"rtol": 1e-13, "atol": 1e-15}, estimate_error=False)[0]


def test_free_body_hairer_lubich_wanner_numbers():
    body = theory.FreeRigidBody(HLW_MOMENTS, HLW_OMEGA0)
    assert body.l2 == pytest.approx(1.0, rel=1e-15)
    assert body.two_t == pytest.approx(1.2942506, abs=1e-7)
    assert body.m == pytest.approx(0.259049, abs=1e-6)
    assert body.period == pytest.approx(10.7315, abs=1e-4)
    assert body.regime == "about_A"


def test_free_body_hlw_100_periods_against_dop853():
    body = theory.FreeRigidBody(HLW_MOMENTS, HLW_OMEGA0, Q0)
    t = np.linspace(0.0, 100 * body.period, 1001)
    sol = _integrated(HLW_MOMENTS, HLW_OMEGA0, Q0, t)
    scale = np.linalg.norm(HLW_OMEGA0)
    assert np.abs(body.omega(t) - sol.omega).max() / scale < 1e-10
    assert quat_angle(body.attitude(t), sol.quaternion).max() < 1e-10      # rad


def test_intermediate_axis_flip_period():
    body = theory.FreeRigidBody([0.3, 0.35, 0.4], [0.1, 15.0, 0.1])
    assert body.period == pytest.approx(12.335, abs=1e-3)


@pytest.mark.parametrize("omega0", [[3.0, -1.0, 0.2], [-3.0, 1.0, -0.2], [0.3, 1.0, -3.0], [-0.3, -1.0, 3.0]])
def test_free_body_both_regimes_and_signs(omega0):
    moments = [0.3, 0.35, 0.4]
    body = theory.FreeRigidBody(moments, omega0, Q0)
    t = np.linspace(0.0, 5 * body.period, 501)
    sol = _integrated(moments, omega0, Q0, t)
    assert np.abs(body.omega(t) - sol.omega).max() / np.linalg.norm(omega0) < 1e-11
    assert quat_angle(body.attitude(t), sol.quaternion).max() < 1e-11


def test_free_body_symmetric_and_steady():
    """A = B (regime about C, k = 0) and a steady spin about C."""
    for moments, omega0 in (([1.0, 1.0, 1.5], [0.2, -0.1, 2.0]), ([1.0, 1.2, 1.5], [0.0, 0.0, 2.0])):
        body = theory.FreeRigidBody(moments, omega0, Q0)
        t = np.linspace(0.0, 20.0, 201)
        sol = _integrated(moments, omega0, Q0, t)
        assert np.abs(body.omega(t) - sol.omega).max() < 1e-11
        assert quat_angle(body.attitude(t), sol.quaternion).max() < 1e-11


def test_free_body_rejects_bad_input():
    with pytest.raises(PhysicsError, match="A <= B <= C"):
        theory.FreeRigidBody([2.0, 1.0, 3.0], [1, 0, 0])
    with pytest.raises(PhysicsError, match="spherical"):
        theory.FreeRigidBody([1.0, 1.0, 1.0], [1, 0, 0])


# --- P92 -------------------------------------------------------------------

def test_start_from_rest_is_eulers_equations_at_rest():
    moments, u, gm, s = np.array([0.8, 0.9, 1.0]), np.array([0.48, 0.6, 0.64]), 3e15, 384400.0
    axis, cos_of, rate = theory.start_from_rest(moments, u, gm, s)
    accel = euler_omega_dot(moments, np.zeros(3), point_mass_torque(moments, s * u, gm))
    np.testing.assert_allclose(axis * rate, accel, rtol=1e-14)
    assert cos_of == pytest.approx(accel @ u / np.linalg.norm(accel), rel=1e-14)


def test_start_from_rest_on_arc_ab_turns_about_c_822():
    moments, gm, s, zeta = np.array([0.8, 0.9, 1.0]), 3e15, 384400.0, math.radians(35)
    axis, _, rate = theory.start_from_rest(moments, [math.cos(zeta), math.sin(zeta), 0.0], gm, s)
    np.testing.assert_allclose(axis, [0, 0, 1], atol=1e-15)
    assert rate == pytest.approx(1.5 * gm * (0.9 - 0.8) * math.sin(2 * zeta) / (1.0 * s**3), rel=1e-14)


# --- P93 -------------------------------------------------------------------

def _libration_ode(n, zeta0, zeta_dot0, t):
    sol = solve_ivp(lambda _, y: [y[1], -n * math.sin(2 * y[0])], (0, t[-1]), [zeta0, zeta_dot0],
                    t_eval=t, rtol=1e-12, atol=1e-14, method="DOP853")
    return sol.y[0]


@pytest.mark.parametrize("energy_over_n, zeta0, case", [
    (-1.0, 0.0, "equilibrium"), (0.0, 0.0, "bounded"), (0.0, 0.3, "bounded"), (0.9, -0.2, "bounded"),
    (2.0, 0.0, "circulation"), (5.0, 0.4, "circulation")])
def test_planar_libration_cases_against_ode(energy_over_n, zeta0, case):
    n = 0.01
    zeta_dot0 = math.sqrt(energy_over_n * n + n * math.cos(2 * zeta0))
    for sign in (1, -1):
        lib = theory.PlanarLibration(n, zeta0, sign * zeta_dot0)
        assert lib.case == case
        t = np.linspace(0, 200, 801)
        np.testing.assert_allclose(lib.zeta(t), _libration_ode(n, zeta0, sign * zeta_dot0, t), atol=1e-9)


def test_planar_libration_bounded_period_and_digression():
    n = 0.01
    lib = theory.PlanarLibration(n, 0.0, math.sqrt(n))              # Euler's C = 0: |zeta| <= 45 deg (§826)
    assert lib.max_digression == pytest.approx(math.pi / 4, rel=1e-14)
    t = np.linspace(0, lib.period, 20001)
    zeta = _libration_ode(n, 0.0, math.sqrt(n), t)
    assert abs(zeta[-1]) < 1e-8 and zeta.max() == pytest.approx(math.pi / 4, abs=1e-7)
    small = theory.PlanarLibration(n, 0.0, 1e-5)                   # §831: returns every pi/sqrt(2n)
    assert small.period / 2 == pytest.approx(small.small_oscillation_return_time(), rel=1e-7)


def test_planar_libration_separatrix_is_eulers_log_tan():
    n = 0.01
    lib = theory.PlanarLibration(n, 0.0, math.sqrt(2 * n))
    assert lib.case == "separatrix"
    zeta = np.radians([10, 45, 80, 89])
    np.testing.assert_allclose(lib.zeta(lib.separatrix_time(zeta)), zeta, rtol=1e-12)
    t = np.linspace(0, 40, 401)                                     # zeta < 80 deg before the instability shows
    np.testing.assert_allclose(lib.zeta(t), _libration_ode(n, 0.0, math.sqrt(2 * n), t), atol=1e-7)


def test_planar_libration_circulation_half_turn_and_euler_series():
    n, mm = 0.01, 16.0                                              # C = mm n (§826, 4th)
    lib = theory.PlanarLibration(n, 0.0, math.sqrt((mm + 1) * n))
    t = np.linspace(0, lib.period, 4001)
    assert _libration_ode(n, 0.0, lib.zeta_dot0, t)[-1] == pytest.approx(math.pi, abs=1e-8)
    zeta = np.linspace(0, math.pi, 7)                               # Euler: t sqrt(n) = zeta/m - sin 2zeta/(4 m^3)
    m = math.sqrt(mm)
    t_euler = (zeta / m - np.sin(2 * zeta) / (4 * m**3)) / math.sqrt(n)
    # the series' first neglected term, 3 cos^2 2zeta/(8 m^5) in dt sqrt(n), shifts zeta by 3 pi/(16 m^4) at pi
    shift = np.abs(lib.zeta(t_euler) - zeta).max()
    assert shift == pytest.approx(3 * math.pi / (16 * m**4), rel=0.1)


def test_planar_libration_rejects_b_below_a():
    with pytest.raises(PhysicsError, match="827"):
        theory.PlanarLibration(-0.01)


# --- P94 -------------------------------------------------------------------

def _forced_ode(n, freq, alpha, beta, t):
    def rhs(tt, y):
        forcing = -freq**2 * alpha * math.sin(freq * tt)
        return [y[1], forcing - n * (1 + beta * math.cos(freq * tt)) * math.sin(2 * y[0])]
    z0 = theory.forced_libration_initial_rate(n, freq, alpha, beta)
    return solve_ivp(rhs, (0, t[-1]), [0.0, z0], t_eval=t, rtol=1e-12, atol=1e-15, method="DOP853").y[0]


def test_forced_libration_against_ode_with_shrinking_remainder():
    n, freq = 0.0078579, math.radians(13.064993)
    t = np.linspace(0, 200, 2001)
    errors = []
    for scale in (1.0, 0.5, 0.25):
        alpha, beta = 0.02 * scale, 0.03 * scale
        first = theory.forced_libration(t, n, freq, alpha)
        second = theory.forced_libration(t, n, freq, alpha, beta)
        ode = _forced_ode(n, freq, alpha, beta, t)
        errors.append(np.abs(second - ode).max() / alpha)
        assert np.abs(second - ode).max() < np.abs(first - ode).max()   # §835 improves on §834
    assert errors[0] < 1e-3
    assert errors[0] / errors[1] == pytest.approx(4, rel=0.1)       # remainder O(alpha^3): relative O(alpha^2)


def test_forced_libration_resonance():
    with pytest.raises(ResonanceError, match="free libration"):
        theory.forced_libration([1.0], 0.02, 0.2, 0.01)


# --- P95 -------------------------------------------------------------------

def test_near_axis_rates_are_eulers_equations_on_the_axis():
    moments, gamma, u, gm, s = np.array([1.2, 0.9, 1.0]), 2.0, np.array([0.6, 0.48, 0.64]), 3e15, 384400.0
    wdot = euler_omega_dot(moments, np.array([gamma, 0, 0]), point_mass_torque(moments, s * u, gm))
    rates = theory.near_axis_rates(moments, gamma, u, gm, s)
    np.testing.assert_allclose(rates, [wdot[0], -wdot[1] / gamma, -wdot[2] / gamma], rtol=1e-14)


def test_pole_rates_symmetric_843a_match_841():
    """§843a (d alpha, alpha d rho) is §841 (d beta, d gamma) rotated by rho."""
    aa, cc, gamma, gm, s, u = 1.1, 1.0, 1.0, 3e15, 384400.0, np.array([0.6, 0.48, 0.64])
    _, d_beta, d_gamma = theory.near_axis_rates(np.array([aa, cc, cc]), gamma, u, gm, s)
    for rho in (0.0, 0.7, 2.5):
        d_alpha, alpha_d_rho = theory.pole_rates_symmetric(aa, cc, gamma, gm, s, rho, u)
        xi_dot = d_alpha * math.cos(rho) - alpha_d_rho * math.sin(rho)     # xi = 90 deg - beta
        eta_dot = d_alpha * math.sin(rho) + alpha_d_rho * math.cos(rho)    # eta = 90 deg - gamma
        assert xi_dot == pytest.approx(-d_beta, rel=1e-13) and eta_dot == pytest.approx(-d_gamma, rel=1e-13)


# --- P96 -------------------------------------------------------------------

def _pole_equations(eps, delta, big_n, n, x0, y0, t):
    """Euler's equations 4 and 5 of §844 with p = n and phi = -delta t."""
    s, c = math.sin(n), math.cos(n)

    def rhs(tt, xy):
        phi = -delta * tt
        return [-eps * xy[1] + big_n * s * math.sin(2 * phi),
                eps * xy[0] + big_n * s * c * (1 + math.cos(2 * phi))]
    return solve_ivp(rhs, (0, t[-1]), [x0, y0], t_eval=t, rtol=1e-12, atol=1e-16, method="DOP853").y


def test_p96_particular_solution_solves_eulers_equations():
    eps, delta, big_n, n = 4.0, 0.2, 1.5e-4, math.radians(23.44)
    p96 = theory.SymmetricPrecession(eps, delta, big_n, n)
    e, f, g = p96.coefficients()
    t = np.linspace(0, 60, 601)
    x, y = _pole_equations(eps, delta, big_n, n, e + f, 0.0, t)
    phi = -delta * t
    np.testing.assert_allclose(x, e + f * np.cos(2 * phi), atol=1e-12)
    np.testing.assert_allclose(y, g * np.sin(2 * phi), atol=1e-12)
    assert p96.precession_rate == pytest.approx(-eps * e / math.sin(n), rel=1e-14)   # d lambda = eps x dt/sin p


def test_p96_resonance_is_detected_and_secular_solution_holds():
    delta, big_n, n = 0.2, 1.5e-4, math.radians(23.44)
    p96 = theory.SymmetricPrecession(2 * delta, delta, big_n, n)
    with pytest.raises(ResonanceError, match="secular"):
        p96.inequalities()
    near = theory.SymmetricPrecession(2 * delta * (1 + 1e-4), delta, big_n, n)
    with pytest.raises(ResonanceError):
        near.coefficients()
    sec = p96.secular()
    f_plus_g = sec["F_plus_G"]
    t = np.linspace(0, 300, 601)
    phi = -delta * t
    # §849 fixes only F + G; take G = 0: x = E + F cos 2phi + a phi sin 2phi, y = a phi cos 2phi.
    x, y = _pole_equations(2 * delta, delta, big_n, n, sec["E"] + f_plus_g, 0.0, t)
    np.testing.assert_allclose(x, sec["E"] + f_plus_g * np.cos(2 * phi) + sec["a"] * phi * np.sin(2 * phi), atol=1e-12)
    np.testing.assert_allclose(y, sec["a"] * phi * np.cos(2 * phi), atol=1e-12)
