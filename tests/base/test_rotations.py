"""Quaternions, matrices and JPL 3-1-3 angles: round trips and kinematics (Euler ch. 15 §809-811)."""
import math

import numpy as np
import pytest

from spinorbit.base.rotations import (
    cross3,
    diag3,
    dot3,
    euler313_from_matrix,
    euler313_from_quat,
    mat_t_vec3,
    matrix_from_euler313,
    matrix_from_quat,
    matvec3,
    omega_body_from_euler313_rates,
    put,
    quat_angle,
    quat_from_euler313,
    quat_from_matrix,
    quat_multiply,
    quat_rate,
    solve3,
)
from tests.units import arcsec, mas

RNG = np.random.default_rng(7)


def test_quaternion_matrix_round_trip():
    for q in RNG.normal(size=(50, 4)):
        q /= np.linalg.norm(q)
        back = quat_from_matrix(matrix_from_quat(q))
        assert quat_angle(q, back) < 1e-15 * 10
        assert np.allclose(matrix_from_quat(q) @ matrix_from_quat(q).T, np.eye(3), atol=1e-15 * 10)


@pytest.mark.parametrize("theta", [1.2, 0.4, 1e-3, 1e-9])
def test_euler313_round_trip_down_to_small_theta(theta):
    phi, psi = 0.7, 2.1
    q = quat_from_euler313(phi, theta, psi)
    back = euler313_from_quat(q)
    assert back[1] == pytest.approx(theta, abs=1e-15 * 10)
    assert quat_angle(q, quat_from_euler313(*back)) < 1e-6 * mas
    if theta > 1e-6:                                                # phi and psi separately resolvable
        assert back[0] == pytest.approx(phi, abs=1e-9) and back[2] == pytest.approx(psi, abs=1e-9)
    else:                                                           # only phi + psi is defined
        assert (back[0] + back[2]) % (2 * math.pi) == pytest.approx(phi + psi, abs=1e-8)


def test_matrix_is_icrf_to_body():
    """M = Rz(psi) Rx(theta) Rz(phi): a pure phi turns the body's x axis towards +y."""
    m = matrix_from_euler313(0.3, 0.0, 0.0)
    np.testing.assert_allclose(m.T @ [1, 0, 0], [math.cos(0.3), math.sin(0.3), 0], atol=1e-16)


def test_body_rates_from_angle_rates_vs_finite_differences():
    angles, rates = np.array([0.4, 0.9, 1.7]), np.array([0.03, -0.02, 0.25])
    h = 1e-5
    m_plus = matrix_from_euler313(*(angles + h * rates))
    m_minus = matrix_from_euler313(*(angles - h * rates))
    m_dot = (m_plus - m_minus) / (2 * h)
    skew = matrix_from_euler313(*angles) @ m_dot.T                  # R^T R' = [omega_body]x with R = M^T
    omega_fd = np.array([skew[2, 1], skew[0, 2], skew[1, 0]])
    np.testing.assert_allclose(omega_body_from_euler313_rates(angles, rates), omega_fd, atol=1e-10)


def test_quat_rate_integrates_a_steady_spin():
    """dq/dt = q (0, w)/2 at constant w gives a rotation by |w| t about w."""
    w, t, n = np.array([0.0, 0.0, 2.0]), 0.5, 2000
    q = np.array([1.0, 0, 0, 0])
    for _ in range(n):                                              # RK4
        h = t / n
        k1 = quat_rate(q, w)
        k2 = quat_rate(q + h / 2 * k1, w)
        k3 = quat_rate(q + h / 2 * k2, w)
        k4 = quat_rate(q + h * k3, w)
        q = q + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    expected = np.array([math.cos(0.5), 0, 0, math.sin(0.5)])
    assert quat_angle(q / np.linalg.norm(q), expected) < 1e-6 * arcsec


def test_quat_angle_resolves_tiny_differences():
    q = np.array([0.3, 0.5, -0.2, 0.7]) / np.linalg.norm([0.3, 0.5, -0.2, 0.7])
    d = np.array([math.cos(5e-12), 0, math.sin(5e-12), 0])
    assert quat_angle(q, -quat_multiply(q, d)) == pytest.approx(1e-11, rel=1e-6)


def test_vector_helpers_against_numpy():
    a, b, m = RNG.normal(size=3), RNG.normal(size=3), RNG.normal(size=(3, 3))
    assert dot3(a, b) == pytest.approx(a @ b, rel=1e-15)
    np.testing.assert_allclose(cross3(a, b), np.cross(a, b), rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose(matvec3(m, a), m @ a, rtol=1e-15, atol=1e-15)
    np.testing.assert_allclose(mat_t_vec3(m, a), m.T @ a, rtol=1e-15, atol=1e-15)
    np.testing.assert_array_equal(diag3(a), np.diag(a))
    out = np.zeros(7)
    put(out[4:7], a)
    np.testing.assert_array_equal(out, np.concatenate([np.zeros(4), a]))
    with pytest.raises(ValueError):
        put(out[:2], a)


def test_solve3_as_accurate_as_lapack_on_inertia_tensors():
    """Cramer's rule on the Moon's inertia (condition ~1.0006) plus a tide-sized symmetric part,
    and on a markedly triaxial tensor: the same solution as LAPACK (np.linalg.solve) to ~20 eps."""
    for moments, scale in (([0.3929, 0.3931, 0.3935], 1e-8), ([0.4, 0.7, 1.0], 1e-2)):
        for _ in range(20):
            sym = RNG.normal(size=(3, 3))
            inertia = np.diag(moments) + scale * (sym + sym.T)
            rhs = RNG.normal(size=3)
            expected = np.linalg.solve(inertia, rhs)
            np.testing.assert_allclose(solve3(inertia, rhs), expected, rtol=0, atol=4e-15 * np.abs(expected).max())


def test_vectorised_euler_angles_match_one_at_a_time():
    angles = np.column_stack([RNG.uniform(0, 2 * np.pi, 5), RNG.uniform(0.1, 3.0, 5), RNG.uniform(0, 2 * np.pi, 5)])
    rates = RNG.normal(size=(5, 3))
    mats = matrix_from_euler313(*angles.T)
    for i in range(5):
        np.testing.assert_array_equal(mats[i], matrix_from_euler313(*angles[i]))
    np.testing.assert_allclose(euler313_from_matrix(mats), angles, atol=1e-14)
    omega = omega_body_from_euler313_rates(angles, rates)
    for i in range(5):
        np.testing.assert_array_equal(omega[i], omega_body_from_euler313_rates(angles[i], rates[i]))


def test_matrices_of_many_quaternions_are_scipys():
    """matrices_from_quats (what Python callers use) against scipy's rotation matrices, for (n, 4) and (4,)."""
    from scipy.spatial.transform import Rotation

    from spinorbit.base.rotations import matrices_from_quats

    q = np.random.default_rng(7).normal(size=(50, 4))
    expected = Rotation.from_quat(q[:, [1, 2, 3, 0]]).as_matrix()           # scipy: scalar last
    assert np.max(np.abs(matrices_from_quats(q) - expected)) < 1e-14
    assert np.max(np.abs(matrices_from_quats(q[3]) - expected[3])) < 1e-14
    assert matrices_from_quats(q.reshape(5, 10, 4)).shape == (5, 10, 3, 3)
