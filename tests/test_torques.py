"""The ch. 16 P91 torque (§815-816) and the §818 force against Euler's formulas and a point cloud."""
import math

import numpy as np
import pytest

from spinorbit.bodies import RigidBody
from spinorbit.torques import figure_force, point_mass_torque, point_masses_torque

GM = 2.9755e15          # km^3/d^2, about the Earth's


def test_components_are_eulers_p_q_r():
    """§815: P = 3 GM (C - B) cos eta cos theta / s^3, Q = 3 GM (A - C) cos zeta cos theta / s^3, R = ..."""
    a, b, c = 0.3930197, 0.3931092, 0.3932677
    zeta, eta = math.radians(50), math.radians(70)
    cos_theta = math.sqrt(1 - math.cos(zeta) ** 2 - math.cos(eta) ** 2)
    cz, ce, ct, s = math.cos(zeta), math.cos(eta), cos_theta, 384400.0
    euler = 3 * GM / s**3 * np.array([(c - b) * ce * ct, (a - c) * cz * ct, (b - a) * cz * ce])
    got = point_mass_torque(np.array([a, b, c]), s * np.array([cz, ce, ct]), GM)
    np.testing.assert_allclose(got, euler, rtol=1e-14)


def test_two_masses_add():
    moments = np.array([1.0, 1.2, 1.5])
    r = np.array([[1e5, 2e5, 3e5], [-4e5, 1e5, 2e5]])
    gm = np.array([GM, 0.3 * GM])
    total = point_mass_torque(moments, r[0], gm[0]) + point_mass_torque(moments, r[1], gm[1])
    np.testing.assert_allclose(point_masses_torque(moments, r, gm), total, rtol=1e-15)


def _cloud(symmetric):
    """A uniform ellipsoid (3, 2, 1) of unit mass as random points; ``symmetric``: closed under r -> -r
    (no odd moments), otherwise a cut ellipsoid (centre of mass moved to the origin)."""
    rng = np.random.default_rng(3)
    p = rng.uniform(-1, 1, size=(60000, 3))
    p = p[np.sum(p * p, axis=1) <= 1] * [3.0, 2.0, 1.0]
    p = np.concatenate([p, -p]) if symmetric else p[p[:, 0] + 0.5 * p[:, 1] > -0.5]
    p = p - p.mean(axis=0)
    m = np.full(len(p), 1.0 / len(p))
    tensor = np.sum(m * np.sum(p * p, axis=1)) * np.eye(3) - np.einsum("i,ij,ik->jk", m, p, p)
    body = RigidBody.from_tensor(tensor)
    return body.moments, p @ body.axes, m                            # points in principal axes


def _brute(points, m, s_vec, gm):
    """Exact force on the cloud and its torque about the centre from a point mass at s_vec."""
    d = s_vec - points
    w = gm * m / np.linalg.norm(d, axis=1) ** 3
    return (w[:, None] * d).sum(axis=0), np.cross(points, w[:, None] * d).sum(axis=0)


@pytest.mark.parametrize("symmetric, order", [(False, 1), (True, 2)])
def test_torque_remainder_shrinks_as_816_says(symmetric, order):
    """The neglected part is O(size/s) of the 1/s^3 torque, O((size/s)^2) without odd moments (§816)."""
    moments, points, m = _cloud(symmetric)
    u = np.array([0.6, 0.48, 0.64])
    errors = []
    for s in (40.0, 80.0, 160.0):
        _, exact = _brute(points, m, s * u, 1.0)
        model = point_mass_torque(moments, s * u, 1.0)
        errors.append(np.linalg.norm(exact - model) / np.linalg.norm(model))
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    assert errors[0] < 0.1
    np.testing.assert_allclose(ratios, 2.0**order, rtol=0.05)


@pytest.mark.parametrize("symmetric, order", [(False, 1), (True, 2)])
def test_figure_force_818_against_cloud(symmetric, order):
    """§818: the force to order 1/s^4; its error relative to the 1/s^4 part shrinks like (size/s)^order."""
    moments, points, m = _cloud(symmetric)
    u = np.array([0.6, 0.48, 0.64])
    errors = []
    for s in (40.0, 80.0, 160.0):
        exact, _ = _brute(points, m, s * u, 1.0)
        model = figure_force(moments, 1.0, s * u, 1.0)
        second = model - u / s**2                                    # the 1/s^4 part
        errors.append(np.linalg.norm(exact - model) / np.linalg.norm(second))
    ratios = np.array(errors[:-1]) / np.array(errors[1:])
    assert errors[0] < 0.1
    np.testing.assert_allclose(ratios, 2.0**order, rtol=0.05)
