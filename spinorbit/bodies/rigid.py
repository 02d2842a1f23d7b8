"""Rigid bodies: inertia tensor -> principal moments and axes (Xambó §6.6, Euler ch. 15).

Moments are kept in whatever unit the caller uses (kg km^2, or units of M R^2);
only their ratios enter the torque-driven rotation (Euler ch. 16 §815).
Principal axes are ordered A <= B <= C (x = smallest moment, z = largest).
"""
from dataclasses import dataclass, field

import numpy as np

from ..base.errors import PhysicsError

_REL_TOL = 1e-12


@dataclass(frozen=True)
class RigidBody:
    """A rigid body by its principal moments (A, B, C) and principal axes.

    ``axes`` has the principal axes as columns, in the frame the inertia tensor
    was given in (identity when built from principal moments).
    """

    moments: np.ndarray
    axes: np.ndarray = field(default_factory=lambda: np.eye(3))
    name: str = "body"

    def __post_init__(self):
        moments = np.asarray(self.moments, dtype=float)
        _check_rigid(moments, self.name)
        object.__setattr__(self, "moments", moments)
        object.__setattr__(self, "axes", np.asarray(self.axes, dtype=float))

    @classmethod
    def from_tensor(cls, tensor, name="body"):
        """Principal moments and axes of a symmetric positive-definite inertia tensor (any axes).

        Xambó §6.6: the inertia tensor of a continuous body in any axes; its
        eigenvectors are the principal axes (Euler ch. 15).
        """
        tensor = np.asarray(tensor, dtype=float)
        if tensor.shape != (3, 3):
            raise PhysicsError(f"{name}: inertia tensor must be 3x3, got shape {tensor.shape}")
        scale = np.abs(tensor).max()
        if not np.allclose(tensor, tensor.T, rtol=0, atol=_REL_TOL * scale):
            raise PhysicsError(f"{name}: inertia tensor is not symmetric: {tensor.tolist()}")
        moments, axes = np.linalg.eigh(0.5 * (tensor + tensor.T))
        if np.linalg.det(axes) < 0:
            axes[:, 0] = -axes[:, 0]
        return cls(moments, axes, name)

    @classmethod
    def from_principal(cls, a, b, c, name="body"):
        """From principal moments A <= B <= C (any unit)."""
        return cls(np.array([a, b, c], dtype=float), name=name)

    @classmethod
    def from_gravity(cls, j2, c22, c_mr2, mass=1.0, radius=1.0, name="body"):
        """From degree-2 gravity coefficients (unnormalised) and C/(M R^2).

        J2 = (C - (A + B)/2)/(M R^2) and C22 = (B - A)/(4 M R^2), so
        A = (c - J2 - 2 C22) M R^2, B = (c - J2 + 2 C22) M R^2, C = c M R^2.
        """
        mr2 = mass * radius**2
        return cls.from_principal(
            (c_mr2 - j2 - 2 * c22) * mr2, (c_mr2 - j2 + 2 * c22) * mr2, c_mr2 * mr2, name
        )

    @classmethod
    def from_ellipsoid(cls, a, b, c, mass=1.0, name="body"):
        """Uniform solid ellipsoid with semi-axes a >= b >= c: A = M (b^2 + c^2)/5, ..."""
        if min(a, b, c) <= 0:
            raise PhysicsError(f"{name}: ellipsoid semi-axes must be positive, got {(a, b, c)}")
        moments = mass / 5.0 * np.array([b * b + c * c, a * a + c * c, a * a + b * b])
        order = np.argsort(moments)
        return cls(moments[order], np.eye(3)[:, order] * _handedness(order), name)

    @property
    def inertia(self):
        """Principal-axis inertia tensor diag(A, B, C)."""
        return np.diag(self.moments)

    @property
    def b_minus_a_over_c(self):
        """Libration parameter gamma = (B - A)/C."""
        a, b, c = self.moments
        return (b - a) / c


def _handedness(order):
    """+1 or -1 so that reordered axes stay right-handed."""
    return np.linalg.det(np.eye(3)[:, order])


def _check_rigid(moments, name):
    """Reject moments that no rigid body has: non-positive, or A + B < C (any order)."""
    if moments.shape != (3,) or not np.all(np.isfinite(moments)):
        raise PhysicsError(f"{name}: need three finite principal moments, got {moments.tolist()}")
    if np.any(moments <= 0):
        raise PhysicsError(
            f"{name}: principal moments must be positive (positive-definite tensor), got {moments.tolist()}"
        )
    if np.any(np.diff(moments) < -_REL_TOL * moments.max()):
        raise PhysicsError(f"{name}: principal moments must be ordered A <= B <= C, got {moments.tolist()}")
    a, b, c = np.sort(moments)
    if a + b < c * (1 - _REL_TOL):
        raise PhysicsError(
            f"{name}: moments {moments.tolist()} violate the triangle inequality A + B >= C "
            "that every mass distribution satisfies"
        )
