"""The rotators' equations of motion (compiled): a rigid body, a mantle with a fluid core, attitude kinematics.

Euler ch. 15 §808/§813: A dw_x/dt + (C - B) w_y w_z = P, and cyclic, i.e. I dw/dt + w x I w = N in principal
axes (Xambó: N = I w' + w x I w); with a time-varying inertia d(I w)/dt + w x I w = N.  The kinematics
§809-811 are carried by the quaternion q (body -> inertial): dq/dt = q (0, w) / 2, plus (0, Omega) q / 2
where the equations hold in a frame turning at Omega (inertial axes) against the inertial one.

The lunar mantle and fluid core (Folkner et al. 2014, IPN PR 42-196, §III, equations (34)-(35); the core
oblate, Williams et al.): with I the whole Moon's inertia, I_c = diag(A_c, A_c, C_c), A_c = C_c (1 - f_c),

    d(I_m w_m)/dt + w_m x I_m w_m = N + N_cmb,      I_m = I - I_c
    N_cmb = k_v (w_c - w_m) + (C_c - A_c) (z . w_c) (z x w_c)
    I_c dw_c/dt + w_m x I_c w_c = -N_cmb                 (w_c in mantle axes, z = (0, 0, 1)).

Every inertia, torque and friction constant in one unit (G I, km^5/d^2 in a System; only ratios enter).
"""
import numpy as np
from numba import njit

from ..base.linker import cached
from ..base.rotations import cross3, diag3, mat_t_vec3, matvec3, quat_rate, solve3


@njit(cache=True, nogil=True)
def euler_omega_dot(moments, omega, torque):
    """dw/dt from Euler's equations (§813) in principal axes: (N - w x I w) / I."""
    a, b, c = moments[0], moments[1], moments[2]
    return np.array([
        (torque[0] - (c - b) * omega[1] * omega[2]) / a,
        (torque[1] - (a - c) * omega[2] * omega[0]) / b,
        (torque[2] - (b - a) * omega[0] * omega[1]) / c,
    ])


@cached(nogil=True)
def distorted_omega_dot(inertia, inertia_rate, omega, torque):
    """dw/dt of a rigid body whose inertia tensor (body axes) changes at ``inertia_rate``: I^-1 (N - w x I w - I' w)."""
    return solve3(inertia, torque - cross3(omega, matvec3(inertia, omega)) - matvec3(inertia_rate, omega))


@cached(nogil=True)
def mantle_and_core_rates(omega, omega_core, inertia, inertia_rate, torque, core_c, core_flattening, friction):
    """(dw_m/dt, dw_c/dt), mantle axes: the torque acts on the whole Moon's inertia (with its distortion and
    rate); the mantle turns with I - I_c, the core by the boundary's torque (module docstring).
    ``core_c``: C_c; ``friction``: k_v, in the unit of the inertia (per day)."""
    a_c = core_c * (1.0 - core_flattening)
    core_moments = np.array([a_c, a_c, core_c])
    mantle = inertia - diag3(core_moments)
    n_cmb = friction * (omega_core - omega) + (core_c - a_c) * omega_core[2] * np.array(
        [-omega_core[1], omega_core[0], 0.0])
    core_rate = (-cross3(omega, core_moments * omega_core) - n_cmb) / core_moments
    rhs_vec = torque + n_cmb - cross3(omega, matvec3(mantle, omega)) - matvec3(inertia_rate, omega)
    return solve3(mantle, rhs_vec), core_rate


@cached(nogil=True)
def quat_rate_in_frame(q, omega, rot, frame_rate):
    """dq/dt of a body turning at ``omega`` (body axes) in a frame that turns at ``frame_rate`` (inertial axes)
    against the inertial one; ``rot`` = the matrix of q."""
    return quat_rate(q, omega + mat_t_vec3(rot, frame_rate))
