"""Euler's equations with attitude kinematics, and their invariants.

State layout (every spin system): ``y = [q_w, q_x, q_y, q_z, w_x, w_y, w_z, ...]``
with q the body-to-inertial unit quaternion and w the body-frame angular
velocity in rad/day; systems with more physics (a lunar fluid core) append
their own components after index 7.

Euler ch. 15 §808/§813: A dw_x/dt + (C - B) w_y w_z = P, and cyclic, i.e.
I dw/dt + w x I w = N in principal axes (Xambó: N = I w' + w x I w).
The kinematics §809-811 are carried by the quaternion (rotations.quat_rate).
"""
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
from numba import njit

from . import terms as term_registry
from .linker import free, link, template
from .rotations import diag3, matrix_from_quat, put, quat_rate, rotate_to_body
from .terms.base import Context, fuse

positions, terms, torque = free("positions", "terms", "torque")    # bound by link()


@njit(cache=True)
def euler_omega_dot(moments, omega, torque):
    """dw/dt from Euler's equations (§813) in principal axes: (N - w x I w) / I."""
    a, b, c = moments[0], moments[1], moments[2]
    return np.array([
        (torque[0] - (c - b) * omega[1] * omega[2]) / a,
        (torque[1] - (a - c) * omega[2] * omega[0]) / b,
        (torque[2] - (b - a) * omega[0] * omega[1]) / c,
    ])


@njit(cache=True)
def _no_torque(t, y, p):
    return np.zeros(3)


@template("torque")
def rigid_body_rhs(t, y, p):
    """dy/dt of a rigid body under ``torque(t, y, p)`` (body frame); ``p[0]`` = principal moments (A, B, C)."""
    moments = p[0]
    dy = np.zeros_like(y)
    put(dy[:4], quat_rate(y[:4], y[4:7]))
    put(dy[4:7], euler_omega_dot(moments, y[4:7], torque(t, y, p)))
    return dy


def make_rigid_body_rhs(torque):
    """Compiled right-hand side dy/dt = rhs(t, y, p) for a rigid body under ``torque``.

    ``torque(t, y, p)`` is a module-level numba function returning the body-frame
    torque; ``p[0]`` must be the principal moments (A, B, C).
    """
    return link(rigid_body_rhs, torque=torque)


@template("positions", "terms")
def figure_torque(t, y, p):
    """Body-frame torque of the fused ``terms`` on a rigid figure; p = (moments, gm (n,), data, term_params, ...)."""
    return terms(t, y, matrix_from_quat(y[:4]), diag3(p[0]), positions(t, p[2]), p[1], p[3])


def make_figure_torque(positions, terms):
    """torque(t, y, p) of the fused ``terms`` (terms.base.fuse) on a rigid figure.

    ``positions(t, data) -> (n, 3)`` is a numba function giving each attracting body's
    position relative to the figure's centre (km, inertial axes) at time t.
    """
    return link(figure_torque, positions=positions, terms=terms)


@dataclass
class SpinSystem:
    """Everything an integrator needs: y' = rhs(t, y, params) from (t0, y0).

    t in TDB days from J2000.0 (or the scene's own time unit for idealised
    scenes); ``torque`` is given separately so that splitting methods can
    alternate free rigid-body flow with torque kicks; it is None when the
    system is not a single rigid body plus external torque (e.g. with a core).
    """

    rhs: Callable
    params: tuple
    t0: float
    y0: np.ndarray
    moments: np.ndarray
    torque: Callable | None = None
    name: str = "system"
    meta: dict = field(default_factory=dict)

    def __post_init__(self):
        self.y0 = np.asarray(self.y0, dtype=float).copy()
        self.y0[:4] /= np.linalg.norm(self.y0[:4])


def torque_free_system(moments, q0, omega0, t0=0.0):
    """A free rigid body (Euler ch. 15 §808)."""
    moments = np.asarray(moments, dtype=float)
    return SpinSystem(make_rigid_body_rhs(_no_torque), (moments,), t0, np.concatenate([q0, omega0]),
                      moments, _no_torque, "free body")


def point_mass_system(moments, orbit, q0, omega0, t0=0.0, name="rigid body under point masses",
                      terms=("point_mass",), body=None):
    """A rigid body under the named terms (default: the P91 torque, §815, of the orbit's point masses)."""
    moments = np.asarray(moments, dtype=float)
    context = Context(body, tuple(getattr(orbit, "names", ())), np.asarray(orbit.gm, dtype=float))
    kernel, term_params = fuse(term_registry.build(terms, context))
    torque = make_figure_torque(orbit.kernel, kernel)
    return SpinSystem(make_rigid_body_rhs(torque), (moments, orbit.gm, orbit.data, term_params), t0,
                      np.concatenate([q0, omega0]), moments, torque, name)


def kinetic_energy(moments, omega):
    """T = (A w_x^2 + B w_y^2 + C w_z^2)/2 for omega of shape (..., 3)."""
    return 0.5 * np.sum(moments * omega**2, axis=-1)


def angular_momentum_inertial(moments, q, omega):
    """Angular momentum in inertial axes, R(q) I w, for arrays of states (..., 4), (..., 3)."""
    q = np.atleast_2d(q)
    omega = np.atleast_2d(omega)
    out = np.array([matrix_from_quat(qi) @ (moments * wi) for qi, wi in zip(q, omega)])
    return out


def invariant_drift(moments, y):
    """Max relative drift of |L|, T and of the inertial L vector over a trajectory y (n, >= 7)."""
    omega = y[:, 4:7]
    energy = kinetic_energy(moments, omega)
    l_body = moments * omega
    l_norm = np.linalg.norm(l_body, axis=1)
    l_inertial = angular_momentum_inertial(moments, y[:, :4], omega)
    return {
        "L_norm_rel_drift": float(np.max(np.abs(l_norm / l_norm[0] - 1))),
        "energy_rel_drift": float(np.max(np.abs(energy / energy[0] - 1))) if energy[0] else 0.0,
        "L_vector_rel_drift": float(np.max(np.linalg.norm(l_inertial - l_inertial[0], axis=1)) / l_norm[0]),
    }


__all__ = [
    "SpinSystem", "euler_omega_dot", "make_rigid_body_rhs", "make_figure_torque",
    "point_mass_system", "torque_free_system", "kinetic_energy", "angular_momentum_inertial",
    "invariant_drift", "rotate_to_body",
]
