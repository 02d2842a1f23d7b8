"""Rigid bodies: inertia tensor in any axes -> principal moments and axes (Xambó §6.6)."""
import numpy as np
import pytest

from spinorbit.base.errors import PhysicsError
from spinorbit.base.rotations import matrix_from_euler313
from spinorbit.bodies import RigidBody


def test_from_tensor_in_rotated_axes_recovers_moments_and_axes():
    moments = np.array([0.3930197, 0.3931092, 0.3932677])
    r = matrix_from_euler313(0.4, 1.1, -2.3).T                     # columns = principal axes
    body = RigidBody.from_tensor(r @ np.diag(moments) @ r.T)
    np.testing.assert_allclose(body.moments, moments, rtol=1e-14)
    for i in range(3):                                              # each axis up to sign
        assert abs(abs(body.axes[:, i] @ r[:, i]) - 1) < 1e-9
    assert np.linalg.det(body.axes) == pytest.approx(1.0, abs=1e-12)


def test_from_gravity_inverts_j2_c22():
    a, b, c = 0.3930197, 0.3931092, 0.3932677                       # DE421 Moon, units M R^2
    body = RigidBody.from_gravity(j2=c - (a + b) / 2, c22=(b - a) / 4, c_mr2=c)
    np.testing.assert_allclose(body.moments, [a, b, c], rtol=1e-14)


def test_from_ellipsoid_matches_point_cloud():
    axes = (3.0, 2.0, 1.0)
    grid = np.linspace(-1, 1, 81)[:-1] + 1 / 80                     # cell centres
    x, y, z = (g.ravel() for g in np.meshgrid(grid * axes[0], grid * axes[1], grid * axes[2], indexing="ij"))
    inside = (x / axes[0]) ** 2 + (y / axes[1]) ** 2 + (z / axes[2]) ** 2 <= 1
    x, y, z = x[inside], y[inside], z[inside]
    m = 1.0 / x.size
    tensor = m * np.array([[np.sum(y * y + z * z), -np.sum(x * y), -np.sum(x * z)],
                           [-np.sum(x * y), np.sum(x * x + z * z), -np.sum(y * z)],
                           [-np.sum(x * z), -np.sum(y * z), np.sum(x * x + y * y)]])
    cloud = RigidBody.from_tensor(tensor)
    exact = RigidBody.from_ellipsoid(*axes)
    np.testing.assert_allclose(cloud.moments, exact.moments, rtol=5e-3)   # grid of 80^3 cells
    np.testing.assert_allclose(np.abs(np.sum(cloud.axes * exact.axes, axis=0)), 1, atol=1e-9)  # same axes


@pytest.mark.parametrize("tensor, words", [
    ([[1, 0.1, 0], [0, 1, 0], [0, 0, 1]], "not symmetric"),
    ([[1, 0, 0], [0, -1, 0], [0, 0, 1]], "positive"),
    ([[1, 0, 0], [0, 1, 0], [0, 0, 2.5]], "triangle"),
])
def test_from_tensor_rejects_non_physical(tensor, words):
    with pytest.raises(PhysicsError, match=words):
        RigidBody.from_tensor(np.array(tensor, dtype=float))
