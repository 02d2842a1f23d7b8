"""The seeds' closed forms: the free rigid body and Euler's Problems 92-96 (ch. 16).

Layer 2 (numpy, scipy.special).  Every function works in the caller's time
unit (days in scenes); angles in rad, rates in rad per time unit.  Euler's
"2g ee" is GM of the centre of forces, so his n = 3 g ee (bb - aa)/(cc s^3)
reads n = (3/2) GM (B - A)/(C s^3) here.
"""
import math

import numpy as np
from scipy.special import ellipj, ellipk, ellipkinc, elliprf, elliprj

from ..base.errors import PhysicsError, ResonanceError
from ..base.rotations import (
    matrices_from_quats,
    matrix_from_euler313,
    quat_from_matrix,
    quat_from_rotation_vector,
    quat_multiply,
)

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
        self._m_l = matrices_from_quats(self.q0) @ self._q_perm.T @ m0

    def _euler_matrix(self, omega, phi):
        """L-frame -> relabelled body frame, M = Rz(psi) Rx(theta) Rz(phi) with l = L_xyz/|L|."""
        l_xyz = (self.moments * omega)[self.perm] / self.l
        theta = math.acos(max(-1.0, min(1.0, l_xyz[2])))
        psi = math.atan2(l_xyz[0] + 0.0, l_xyz[1] + 0.0)    # + 0.0: no signed zeros in a steady spin
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


def axisymmetric_attitude(moments, omega0, q0, t, s):
    """Attitude (n, 4) at times t of a torque-free body symmetric about body axis s (the other two moments equal).

    With body L0, q(t) = q0 E(L0 t / I_p) E((1/I_s - 1/I_p) L_s t e_s), E(w) the unit quaternion
    of rotation vector w (the body L rotates about e_s by -(1/I_s - 1/I_p) L_s t).  Written with
    I_p - I_s, so that it stays exact for a flattening of 1e-8 (the elliptic form loses digits there).
    """
    moments, omega0 = np.asarray(moments, dtype=float), np.asarray(omega0, dtype=float)
    i_s, i_p = moments[s], moments[(s + 1) % 3]
    l0 = moments * omega0
    t = np.asarray(t, dtype=float)[:, None]
    first = quat_from_rotation_vector(l0 / i_p * t)
    second = quat_from_rotation_vector((i_p - i_s) / (i_s * i_p) * l0[s] * np.eye(3)[s] * t)
    return np.array([quat_multiply(quat_multiply(np.asarray(q0, dtype=float), a), b) for a, b in zip(first, second)])


# --- Problem 92: first motion of a body at rest (§820-823, §806) -------------

def libration_n(moments, gm, s):
    """Euler's n = 3 g ee (bb - aa)/(cc s^3) = (3/2) GM (B - A)/(C s^3), rad^2 per time^2 (§826)."""
    a, b, c = moments
    return 1.5 * gm * (b - a) / (c * s**3)


def start_from_rest(moments, u_body, gm, s):
    """Axis a body at rest begins to turn about, and its angular acceleration (§820, §806).

    ``u_body`` = direction to the centre of forces in principal axes (cos zeta,
    cos eta, cos theta).  Returns (axis, cos_of, rate): axis = (cos alpha,
    cos beta, cos gamma) proportional to (P/A, Q/B, R/C); cos_of = cos OF, the
    axis's angle from F; rate = d gamma'/dt = |(P/A, Q/B, R/C)| (rad/time^2).
    The axis is undefined (zero vector) when F lies on a principal axis.
    """
    moments = np.asarray(moments, dtype=float)
    u = np.asarray(u_body, dtype=float) / np.linalg.norm(u_body)
    a, b, c = moments
    k = 3 * gm / s**3
    torque = k * np.array([(c - b) * u[1] * u[2], (a - c) * u[2] * u[0], (b - a) * u[0] * u[1]])
    accel = torque / moments
    rate = float(np.linalg.norm(accel))
    axis = accel / rate if rate > 0 else np.zeros(3)
    return axis, float(axis @ u), rate


# --- Problem 93: planar libration on a circular orbit (§825-831) -------------

class PlanarLibration:
    """zeta'' + n sin 2 zeta = 0 (§825), zeta = AF the angle from the axis A to F.

    ``energy`` is Euler's constant C = zeta'^2 - n cos 2 zeta; the four cases
    of §826: ``"equilibrium"`` (C = -n), ``"bounded"`` (-n < C < n, C = 0 is
    Euler's 2nd case), ``"separatrix"`` (C = n), ``"circulation"`` (C > n).
    As a pendulum in 2 zeta with frequency sqrt(2n), every case has a closed
    form in Jacobi functions (scipy.special.ellipj).  Requires n > 0 (B > A;
    for B < A use zeta -> zeta + 90 deg, §827).
    """

    def __init__(self, n, zeta0=0.0, zeta_dot0=0.0, rel_tol=1e-12):
        if not n > 0:
            raise PhysicsError(f"PlanarLibration: n must be positive (B > A), got {n}; "
                               "for B < A measure zeta from the axis B (§827)")
        self.n, self.zeta0, self.zeta_dot0 = float(n), float(zeta0), float(zeta_dot0)
        self.energy = zeta_dot0**2 - n * math.cos(2 * zeta0)
        self.w0 = math.sqrt(2 * n)
        c = self.energy / n
        if c < -1 + rel_tol:
            self.case = "equilibrium"
        elif abs(c - 1) <= rel_tol:
            self.case = "separatrix"
        else:
            self.case = "bounded" if c < 1 else "circulation"
        self.sign = 1.0 if zeta_dot0 >= 0 else -1.0
        if self.case == "bounded":
            self.m = (1 + c) / 2                                  # k^2 = sin^2(max digression)
            k = math.sqrt(self.m)
            sn0 = max(-1.0, min(1.0, math.sin(zeta0) / k))
            dn0 = math.sqrt(1 - self.m * sn0**2)
            cn0 = zeta_dot0 * math.cos(zeta0) / (k * self.w0 * dn0)
            self.u0 = float(ellipkinc(math.atan2(sn0, cn0), self.m))
        elif self.case == "circulation":
            self.m = 2 * n / (self.energy + n)
            self.u0 = float(ellipkinc(zeta0, self.m))
        elif self.case == "separatrix":
            self.m = 1.0
            self.u0 = math.asinh(math.tan(zeta0))

    @property
    def max_digression(self):
        """Largest |zeta| (rad): arcsin k for bounded motion, 90 deg at the separatrix (§826)."""
        if self.case == "equilibrium":
            return abs(self.zeta0)
        if self.case == "bounded":
            return math.asin(math.sqrt(self.m))
        return math.pi / 2 if self.case == "separatrix" else math.inf

    @property
    def period(self):
        """Period of zeta: 4 K(k^2)/sqrt(2n) for bounded motion (twice the time between
        returns to F; small oscillations: 2 pi/sqrt(2n), §831); for circulation the
        time for zeta to advance by pi, 2 K(m)/sqrt(C + n) with m = 2n/(C + n)."""
        if self.case == "bounded":
            return 4 * ellipk(self.m) / self.w0
        if self.case == "circulation":
            return 2 * ellipk(self.m) / math.sqrt(self.energy + self.n)
        return math.inf

    def small_oscillation_return_time(self):
        """Euler's time between returns of A to F for small oscillations, pi/sqrt(2n) (§831)."""
        return math.pi / self.w0

    def separatrix_time(self, zeta):
        """Euler's t = ln tan(45 deg + zeta/2)/sqrt(2n), time from zeta = 0 to zeta (§826, 3rd)."""
        return np.log(np.tan(math.pi / 4 + np.asarray(zeta) / 2)) / self.w0

    def zeta(self, t):
        """zeta(t) (rad) from t = 0; continuous (unwrapped) in the circulating case."""
        t = np.asarray(t, dtype=float)
        if self.case == "equilibrium":
            return np.full_like(t, self.zeta0)
        if self.case == "bounded":
            sn, _, _, _ = ellipj(self.w0 * t + self.u0, self.m)
            return np.arcsin(math.sqrt(self.m) * sn)
        if self.case == "separatrix":
            return np.arctan(np.sinh(self.sign * self.w0 * t + self.u0))
        _, _, _, ph = ellipj(self.sign * math.sqrt(self.energy + self.n) * t + self.u0, self.m)
        return ph


# --- Problem 94: libration forced by an uneven orbit (§833-836) --------------

def forced_libration(t, n, a_freq, alpha, beta=0.0):
    """Euler's zeta(t) for XF = delta t + alpha sin At, 1/s^3 = (1 + beta cos At)/f^3.

    First order (§834): zeta = A^2 alpha/(A^2 - 2n) sin At.  Second order in
    alpha beta (§835): + p sin 2At with p = n m beta/(4A^2 - 2n), m the first
    amplitude; Euler prints n alpha beta/(4(A^2 - 2n)), the same for n << A^2.
    Raises ResonanceError at A^2 = 2n (free libration frequency).
    """
    a2 = a_freq**2
    for denominator, name in ((a2 - 2 * n, "A^2 = 2n"), (4 * a2 - 2 * n, "4A^2 = 2n")):
        if abs(denominator) <= 1e-12 * max(a2, abs(n)):
            raise ResonanceError(f"forced_libration: {name}: the forcing is at the free libration "
                                 "frequency sqrt(2n); the §834 amplitude is infinite")
    m = a2 * alpha / (a2 - 2 * n)
    p = n * m * beta / (4 * a2 - 2 * n)
    t = np.asarray(t, dtype=float)
    return m * np.sin(a_freq * t) + p * np.sin(2 * a_freq * t)


def forced_libration_initial_rate(n, a_freq, alpha, beta=0.0):
    """zeta'(0) of forced_libration: the start that excites no free libration (§838)."""
    a2 = a_freq**2
    m = a2 * alpha / (a2 - 2 * n)
    return a_freq * m + 2 * a_freq * n * m * beta / (4 * a2 - 2 * n)


# --- Problem 95: motion near a principal axis (§840-843a) --------------------

def near_axis_rates(moments, gamma_prime, u_body, gm, s):
    """Momentary changes when the body turns at gamma_prime about (nearly) its x axis (§840).

    Euler's A, B, C are the body axes x, y, z here (any moments, the turning
    axis is x).  Returns (d gamma'/dt, d beta/dt, d gamma/dt): the rate of the
    angular speed and of the arcs from the rotation pole O to the poles B
    and C (rad/time), from 6 g ee = 3 GM.  Exact when O is on the x axis.
    """
    a, b, c = moments
    u = np.asarray(u_body, dtype=float) / np.linalg.norm(u_body)
    k = 3 * gm / s**3
    return (k * (c - b) * u[1] * u[2] / a,
            -k * (a - c) * u[0] * u[2] / (b * gamma_prime),
            -k * (b - a) * u[0] * u[1] / (c * gamma_prime))


def pole_rates_symmetric(a_polar, c_equatorial, gamma_prime, gm, s, rho, u_body):
    """§843a for B = C: (d alpha/dt, alpha d rho/dt) of the pole O near the singular axis A.

    alpha = AO, rho = angle BAO; u_body = (cos zeta, cos eta, cos theta) of F in
    Euler's axes (A, B, C).  N = 3 g ee (aa - cc)/(gamma' cc s^3) = (3/2) GM (aa - cc)/(gamma' cc s^3).
    The free rotation of O about A at (aa - cc)/cc gamma' is not included (Euler
    takes y = z = 0 at the instant), so these hold for alpha -> 0.
    """
    big_n = 1.5 * gm * (a_polar - c_equatorial) / (gamma_prime * c_equatorial * s**3)
    cz, ce, ct = np.asarray(u_body, dtype=float) / np.linalg.norm(u_body)
    return (2 * big_n * cz * (math.cos(rho) * ct - math.sin(rho) * ce),
            -2 * big_n * cz * (math.sin(rho) * ct + math.cos(rho) * ce))


# --- Problem 96: precession and nutation of a symmetric spinner (§844-849) ---

def precession_constant(gm, s, eps, aa, cc):
    """Euler's N = (3/2) GM (aa - cc)/(eps cc s^3) of P96 (§844), rad per time unit: aa the polar moment,
    cc the equatorial one, eps the spin rate, F at distance s.  The mean precession is N cos n
    (SymmetricPrecession; N cos n cc/aa with the gyroscopic ratio aa/cc)."""
    return 1.5 * gm * (aa - cc) / (eps * cc * s**3)


class SymmetricPrecession:
    """Euler's solution of P96 (§844) without the diurnal terms (h = 0).

    ``eps`` spin rate, ``delta`` orbit rate of F (same sense), ``big_n`` =
    N = (3/2) GM (aa - cc)/(eps cc s^3) (aa polar, cc equatorial moment), ``n``
    mean arc ZA (obliquity, rad), ``m`` mean longitude XZA at t = 0.  In the
    equations for x = alpha cos omega, y = alpha sin omega Euler's rate eps
    becomes ``eps * ratio``; ratio = 1 is Euler's text, ratio = aa/cc adds the
    free rotation of the pole in the body (C - A)/A eps that §841 drops; it
    turns the mean precession N cos n into the gyroscopic N cos n cc/aa.

    ``inequalities()`` raises ResonanceError near eps = 2 delta: there the 2 phi
    amplitudes exceed ``max_alpha`` (the §845 small-alpha hypothesis fails, and
    at equality they are infinite, §849), so a number would be meaningless;
    ``secular()`` gives §849's singular solution instead.
    """

    def __init__(self, eps, delta, big_n, n, m=0.0, ratio=1.0, max_alpha=0.05):
        self.eps, self.delta, self.big_n, self.n, self.m = eps, delta, big_n, n, m
        self.eps_f, self.max_alpha = eps * ratio, max_alpha

    @property
    def precession_rate(self):
        """Mean regression of A about Z, rad/time: N cos n (§846) times eps/eps_f."""
        return self.big_n * math.cos(self.n) * self.eps / self.eps_f

    def coefficients(self):
        """(E, F, G) of x = E + F cos 2phi, y = G sin 2phi (§844); ResonanceError near eps = 2 delta."""
        s, c = math.sin(self.n), math.cos(self.n)
        e, d, nn = self.eps_f, self.delta, self.big_n
        denominator = e * e - 4 * d * d
        big_e = -nn * s * c / e
        bound = nn * s * (e + 2 * d) / abs(denominator) if denominator else math.inf
        if bound > self.max_alpha:
            raise ResonanceError(
                f"P96 at eps = {self.eps:.9g}, 2 delta = {2 * d:.9g}: the 2phi terms reach {bound:.3g} rad "
                f"> {self.max_alpha} (eps^2 - 4 delta^2 = {denominator:.3g}); Euler's formulas need eps far "
                "from 2 delta (§849). Use SymmetricPrecession.secular() for the singular solution.")
        return big_e, -nn * s * (e * c + 2 * d) / denominator, nn * s * (e + 2 * d * c) / denominator

    def inequalities(self):
        """Amplitudes of the 2phi inequalities: ZA half-range (§847; §849 gives the full range
        twice this) and XZA longitude amplitude (rad), with phi = FZA."""
        _, f, g = self.coefficients()
        return {"za_half_range": self.eps * abs(g) / (2 * self.delta),
                "xza_amplitude": self.eps * abs(f) / (2 * self.delta * math.sin(self.n))}

    def secular(self):
        """§849 at eps = 2 delta: x = E + F cos 2phi + a phi sin 2phi, y = G sin 2phi + a phi cos 2phi.

        Returns E = -N sin n cos n/(2 delta), a = -N sin n (1 + cos n)/(2 delta),
        F + G = N sin n (1 - cos n)/(4 delta), and ``growth_rate`` = |a| delta,
        the linear growth per unit time of the 2phi amplitude of alpha and of ZA.
        """
        s, c, d, nn = math.sin(self.n), math.cos(self.n), self.delta, self.big_n
        a = -nn * s * (1 + c) / (2 * d)
        return {"E": -nn * s * c / (2 * d), "a": a, "F_plus_G": nn * s * (1 - c) / (4 * d),
                "growth_rate": abs(a) * d}


def p96_initial_state(n, eps, x0, y0):
    """(q0, body omega0) of P96's spinner: figure axis at ZA = n, XZA = 0 (orbit plane = x-y), omega =
    eps A + A x v_A with the pole velocity v_A = eps (-y e_p + x e_lambda) of Euler's dp = -eps y dt,
    sin p d lambda = eps x dt (§844); x0, y0 from SymmetricPrecession.coefficients (x0 = E + F)."""
    a_hat = np.array([math.sin(n), 0.0, math.cos(n)])
    e_p, e_lam = np.array([math.cos(n), 0.0, -math.sin(n)]), np.array([0.0, 1.0, 0.0])
    omega_inertial = eps * a_hat + np.cross(a_hat, eps * (-y0 * e_p + x0 * e_lam))
    q0 = np.array([math.cos(n / 2), 0.0, math.sin(n / 2), 0.0])
    return q0, matrices_from_quats(q0).T @ omega_inertial
