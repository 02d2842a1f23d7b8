"""A free rigid body's invariants along a trajectory: kinetic energy, angular momentum, and their drift.

Euler ch. 15 §808: without torque the kinetic energy T = (A w_x^2 + B w_y^2 + C w_z^2)/2 and the angular
momentum L = R(q) I w (inertial axes) are constant; their drift over a run measures the integrator.
"""
import numpy as np

from ..base.rotations import matrices_from_quats


def kinetic_energy(moments, omega):
    """T = (A w_x^2 + B w_y^2 + C w_z^2)/2 for omega of shape (..., 3)."""
    return 0.5 * np.sum(moments * omega**2, axis=-1)


def angular_momentum_inertial(moments, q, omega):
    """Angular momentum in inertial axes, R(q) I w, for arrays of states (..., 4), (..., 3)."""
    q, omega = np.atleast_2d(q), np.atleast_2d(omega)
    return np.einsum("nij,nj->ni", matrices_from_quats(q), moments * omega)


def invariant_drift(moments, q, omega):
    """Max relative drift of |L|, T and of the inertial L vector over attitudes q (n, 4) and rates omega (n, 3)."""
    energy = kinetic_energy(moments, omega)
    l_norm = np.linalg.norm(moments * omega, axis=1)
    l_inertial = angular_momentum_inertial(moments, q, omega)
    return {
        "L_norm_rel_drift": float(np.max(np.abs(l_norm / l_norm[0] - 1))),
        "energy_rel_drift": float(np.max(np.abs(energy / energy[0] - 1))) if energy[0] else 0.0,
        "L_vector_rel_drift": float(np.max(np.linalg.norm(l_inertial - l_inertial[0], axis=1)) / l_norm[0]),
    }
