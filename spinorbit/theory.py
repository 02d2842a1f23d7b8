"""The seeds' closed forms: the free rigid body and Euler's Problems 92-96 (ch. 16).

Layer 2 (numpy, scipy.special).  Every function works in the caller's time
unit (days in scenes); angles in rad, rates in rad per time unit.  Euler's
"2g ee" is GM of the centre of forces, so his n = 3 g ee (bb - aa)/(cc s^3)
reads n = (3/2) GM (B - A)/(C s^3) here.
"""
import math

import numpy as np
from scipy.special import ellipj, ellipk, ellipkinc, elliprf, elliprj

from .errors import PhysicsError, ResonanceError
from .rotations import matrix_from_euler313, matrix_from_quat, quat_from_matrix

_REL = 1e-13


# --- Torque-free motion (ch. 15 §808; Euler 1758 via Cayley) ----------------

class FreeRigidBody:
    """Torque-free motion of a rigid body in closed form (Jacobi elliptic functions).

    ``moments`` = (A, B, C), A <= B <= C; ``omega0`` body angular velocity at
    t = 0 (rad per time unit); ``q0`` body -> inertial quaternion at t = 0.
    ``regime`` tells which side of L^2 = 2 T B the motion lies on:
    ``"about_C"`` (L^2 > 2 T B, the pole circles the axis of largest moment),
    ``"about_A"`` (L^2 < 2 T B) or ``"separatrix"`` (L^2 = 2 T B to 1e-13).

    The attitude is built from the fixed direction of L (Euler 1758: the
    motion "without the invariable plane" reduces to one angle about L) and
    the rotation angle about L, whose rate is
    L (2T - I_z w_z^2)/(L^2 - I_z^2 w_z^2) (z = the axis the pole circles);
    its integral is an elliptic integral of the third kind, evaluated with
    Carlson's R_F and R_J (scipy.special.elliprf, elliprj).
    """

    def __init__(self, moments, omega0, q0=(1.0, 0.0, 0.0, 0.0)):
        moments = np.asarray(moments, dtype=float)
        omega0 = np.asarray(omega0, dtype=float)
        if moments.shape != (3,) or np.any(moments <= 0) or np.any(np.diff(moments) < 0):
            raise PhysicsError(f"FreeRigidBody: moments must be 0 < A <= B <= C, got {moments.tolist()}")
        if omega0.shape != (3,) or not np.any(omega0):
            raise PhysicsError(f"FreeRigidBody: omega0 must be a non-zero 3-vector, got {omega0.tolist()}")
        if moments[0] == moments[2]:
            raise PhysicsError("FreeRigidBody: a spherical body (A = B = C) just spins uniformly; "
                               "no elliptic solution needed")
        self.moments, self.omega0 = moments, omega0
        self.q0 = np.asarray(q0, dtype=float) / np.linalg.norm(q0)
        a, b, c = moments
        self.l2 = float(np.sum((moments * omega0) ** 2))
        self.two_t = float(np.sum(moments * omega0**2))
        side = self.l2 - self.two_t * b
        if abs(side) <= _REL * self.l2:
            self.regime = "separatrix"
        else:
            self.regime = "about_C" if side > 0 else "about_A"
        # Cyclic relabelling (x, y, z) of the body axes so that z is the axis the pole circles
        # (dn), x carries cn and y carries sn (regime about_A: x = B, y = C, z = A, sn/cn swapped).
        if self.regime == "about_A":
            self.perm = np.array([1, 2, 0])
            i_dn, i_cn, i_sn = 0, 2, 1
        else:
            self.perm = np.array([0, 1, 2])
            i_dn, i_cn, i_sn = 2, 0, 1
        l2, tt = self.l2, self.two_t
        self.m = float(min(1.0, (b - a) * (c * tt - l2) / ((c - b) * (l2 - a * tt)))) \
            if self.regime == "about_C" else \
            (1.0 if self.regime == "separatrix" else float((c - b) * (l2 - a * tt) / ((b - a) * (c * tt - l2))))
        if self.regime == "about_A":
            self.nu = math.sqrt((b - a) * (c * tt - l2) / (a * b * c))
        else:
            self.nu = math.sqrt((c - b) * max(l2 - a * tt, 0.0) / (a * b * c))
        amp = np.empty(3)
        amp[0] = math.sqrt(max(c * tt - l2, 0.0) / (a * (c - a)))
        amp[1] = math.sqrt(max(c * tt - l2, 0.0) / (b * (c - b))) if self.regime != "about_A" else \
            math.sqrt(max(l2 - a * tt, 0.0) / (b * (b - a)))
        amp[2] = math.sqrt(max(l2 - a * tt, 0.0) / (c * (c - a)))
        self._amp, self._idx = amp, (i_cn, i_sn, i_dn)
        # Signs: w_cn = a cn, w_sn = s a sn, w_dn = s a dn with s = sign(w_dn(0)) (Euler's equations).
        self._s = 1.0 if omega0[i_dn] >= 0 else -1.0
        sn0 = omega0[i_sn] / (self._s * amp[i_sn]) if amp[i_sn] > 0 else 0.0
        cn0 = omega0[i_cn] / amp[i_cn] if amp[i_cn] > 0 else 1.0
        self.u0 = float(ellipkinc(math.atan2(sn0, cn0), self.m))
        self.K = float(ellipk(self.m))
        self.period = 4 * self.K / self.nu if self.nu > 0 and self.m < 1 else math.inf
        self._attitude_setup()

    def omega(self, t):
        """Body angular velocity (n, 3) at times t (from t = 0), rad per time unit."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        sn, cn, dn, _ = ellipj(self.nu * t + self.u0, self.m)
        i_cn, i_sn, i_dn = self._idx
        out = np.empty((t.size, 3))
        out[:, i_cn] = self._amp[i_cn] * cn
        out[:, i_sn] = self._s * self._amp[i_sn] * sn
        out[:, i_dn] = self._s * self._amp[i_dn] * dn
        return out

    def _attitude_setup(self):
        i_z = self._idx[2]
        self.i_z = self.moments[i_z]
        self.l = math.sqrt(self.l2)
        # 1/(L^2 - I_z^2 w_z^2) = 1/(P + Q sn^2) with w_z^2 = a_z^2 (1 - m sn^2).
        a_z2 = self._amp[i_z] ** 2
        self._p = self.l2 - self.i_z**2 * a_z2
        self._q = self.i_z**2 * a_z2 * self.m
        self._coef = self.l * (self.two_t * self.i_z - self.l2) / self.i_z
        if abs(self._coef) <= _REL * self.l**3 / self.i_z or self._p <= 0:
            self._coef = 0.0                     # steady rotation about a principal axis
        self._q_perm = np.eye(3)[self.perm]      # v_xyz = Pm v_body
        m0 = self._euler_matrix(self.omega(0.0)[0], 0.0)
        self._m_l = matrix_from_quat(self.q0) @ self._q_perm.T @ m0

    def _euler_matrix(self, omega, phi):
        """L-frame -> relabelled body frame, M = Rz(psi) Rx(theta) Rz(phi) with l = L_xyz/|L|."""
        l_xyz = (self.moments * omega)[self.perm] / self.l
        theta = math.acos(max(-1.0, min(1.0, l_xyz[2])))
        psi = math.atan2(l_xyz[0], l_xyz[1])
        return matrix_from_euler313(phi, theta, psi)

    def _g(self, u):
        """G(u) = integral_0^u dv / (P + Q sn^2 v), extended across periods 2K."""
        if self.m >= 1.0:
            j, r = np.zeros_like(u), u
        else:
            j = np.round(u / (2 * self.K))
            r = u - 2 * self.K * j
        sn, cn, dn, _ = ellipj(r, self.m)
        n = -self._q / self._p
        part = sn * elliprf(cn**2, dn**2, 1.0) + n / 3 * sn**3 * elliprj(cn**2, dn**2, 1.0, 1.0 - n * sn**2)
        if self.m < 1.0:
            complete = elliprf(0.0, 1.0 - self.m, 1.0) + n / 3 * elliprj(0.0, 1.0 - self.m, 1.0, 1.0 - n)
            part = part + 2 * j * complete
        return part / self._p

    def angle_about_l(self, t):
        """Rotation angle phi(t) about L (rad), phi(0) = 0 (Landau-Lifshitz §37 form)."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        phi = self.l / self.i_z * t
        if self._coef:
            phi = phi + self._coef * (self._g(self.nu * t + self.u0) - self._g(np.array([self.u0]))) / self.nu
        return phi

    def attitude(self, t):
        """Body -> inertial unit quaternions (n, 4) at times t (from t = 0)."""
        t = np.atleast_1d(np.asarray(t, dtype=float))
        omega, phi = self.omega(t), self.angle_about_l(t)
        out = np.empty((t.size, 4))
        for i in range(t.size):
            r = self._m_l @ self._euler_matrix(omega[i], phi[i]).T @ self._q_perm
            out[i] = quat_from_matrix(r)
        return out
