"""Structure-preserving splitting for a rigid body under an external torque (Lie-group method).

The Hamiltonian of a torqued rigid body splits into the free rigid body
(Euler ch. 15 §808) and the torque potential (ch. 16 P91).  One step
alternates their exact flows:

* **kick** ``K(h)``: body angular momentum ``L += h N(t, q)`` at fixed attitude
  (the torque depends on time and attitude only, e.g. point masses);
* **free flow** ``D(h)``: the free body, itself split into rotations whose
  flows are exact.  Every sub-flow has a body angular velocity ``w`` constant
  over the sub-step, so the attitude advances by ``q <- q * exp(w h / 2)`` and
  the body momentum rotates by ``-|w| h`` about ``w``: both are rotations, so
  ``|L|`` is kept to rounding and the quaternion stays unit.

Free-flow splittings (option ``free_flow``):

``"symmetric"`` (default)
    H = [(L_i^2 + L_j^2)/(2 I_i) + L_s^2/(2 I_s)] + (1/(2 I_j) - 1/(2 I_i)) L_j^2,
    where s is the axis whose two companions i, j have the closest moments.
    The bracket is an axisymmetric body, solved exactly (rotation about L plus
    rotation about axis s); the remainder is a rotation about axis j whose rate
    is proportional to I_i - I_j, so the splitting error vanishes for a
    symmetric body and stays small for a nearly symmetric fast spinner.
``"axes"``
    H = sum_k L_k^2 / (2 I_k), rotations about the three axes in turn
    (Touma & Wisdom 1994; McLachlan 1993; Dullweber, Leimkuhler & McLachlan 1997).
    Each rotation angle is ~ |w| h, so the error grows with the spin rate:
    it fails for a fast, nearly symmetric spinner (measured in
    benchmarks/RESULTS.md and tests/test_integrators.py).

Frame rate: where the body's equations hold in a frame turning at a rate ``Omega``
(rad/d, inertial axes) with respect to the axes of q (the Earth's geodesic precession,
which the System writes as ``system.frame_rate(t, y, p)``), q' gains Omega q / 2.  Its flow
``q <- exp(Omega h / 2) q`` is a left multiplication, which commutes with the free
flow's right multiplications and leaves the body momentum alone, so the drift
applies both exactly and the orders are unchanged; a rate that varies (the geodesic
nutation's annual term) is taken at each sub-step's midpoint.

Methods: ``strang`` (K(h/2) D(h) K(h/2), order 2), ``yoshida4`` (triple-jump
composition of Strang, order 4, Yoshida 1990) and ``suzuki4`` (five-stage
composition, order 4, Suzuki 1990; smaller error constant).  All are symplectic
and time-reversible: the energy of a torque-free run has bounded error, no drift.
Time enters the kicks only (t advances with the free flow).
"""
import math
import time

import numpy as np
from numba import njit

from ..base.errors import InputError, IntegrationError
from ..base.linker import free, link, template
from ..base.progress import progress
from ..base.rotations import put
from .base import Integrator, Trajectory, output_chunks
from .options import FREE_FLOW, MAX_STEPS, STEP

torque, frame_rate = free("torque", "frame_rate")    # bound by link()

FREE_FLOWS = ("symmetric", "axes")


@njit(cache=True)
def _add(x, c, m, delta):
    """In place: x[m] += delta by compensated (Kahan) summation, the lost low-order bits kept in c[m]."""
    y = delta - c[m]
    total = x[m] + y
    c[m] = (total - x[m]) - y
    x[m] = total


@njit(cache=True)
def _spin(q, wx, wy, wz, h):
    """In place: q <- q * exp(w h/2), w constant (body frame, rad/d); q moves by its increment (no cos - 1)."""
    rate = math.sqrt(wx * wx + wy * wy + wz * wz)
    if rate == 0.0:
        return
    s = math.sin(0.25 * rate * h)
    b0 = -2.0 * s * s                                  # cos(rate h / 2) - 1
    s = math.sin(0.5 * rate * h) / rate
    b1, b2, b3 = s * wx, s * wy, s * wz
    a0, a1, a2, a3 = q[0], q[1], q[2], q[3]
    q[0] += a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3
    q[1] += a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2
    q[2] += a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1
    q[3] += a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0


@njit(cache=True)
def _axis_rotation(q, l, lc, k, rate_per_l, h):
    """In place: flow of H = rate_per_l L_k^2 / 2, a rotation by angle a = rate_per_l L_k h about body axis k.

    q <- q * exp(a e_k / 2) and L turns by -a about e_k, both applied as increments
    formed from half-angle sines, L's with compensated sums (lc): rounding stays at a
    few ulps over ~1e8 sub-rotations.
    """
    angle = rate_per_l * l[k] * h
    s = math.sin(0.25 * angle)
    b0, bk = -2.0 * s * s, math.sin(0.5 * angle)      # cos(a/2) - 1, sin(a/2)
    i, j = (k + 1) % 3, (k + 2) % 3
    a0, ak, ai, aj = q[0], q[k + 1], q[i + 1], q[j + 1]
    q[0] += a0 * b0 - ak * bk
    q[k + 1] += a0 * bk + ak * b0
    q[i + 1] += ai * b0 + aj * bk
    q[j + 1] += aj * b0 - ai * bk
    c1, sn = -2.0 * bk * bk, math.sin(angle)          # cos(a) - 1, sin(a)
    li, lj = l[i], l[j]
    _add(l, lc, i, li * c1 + lj * sn)
    _add(l, lc, j, lj * c1 - li * sn)


@njit(cache=True)
def _free_flow(q, l, lc, moments, h, symmetric, s, i, j):
    """In place: symmetric (2nd-order) splitting of the free rigid body over h; see the module docstring."""
    if symmetric:
        _axis_rotation(q, l, lc, j, 1.0 / moments[j] - 1.0 / moments[i], 0.5 * h)
        _spin(q, l[0] / moments[i], l[1] / moments[i], l[2] / moments[i], h)   # |L|^2 / (2 I_i): L fixed
        _axis_rotation(q, l, lc, s, 1.0 / moments[s] - 1.0 / moments[i], h)   # axisymmetric part
        _axis_rotation(q, l, lc, j, 1.0 / moments[j] - 1.0 / moments[i], 0.5 * h)
    else:
        _axis_rotation(q, l, lc, 0, 1.0 / moments[0], 0.5 * h)
        _axis_rotation(q, l, lc, 1, 1.0 / moments[1], 0.5 * h)
        _axis_rotation(q, l, lc, 2, 1.0 / moments[2], h)
        _axis_rotation(q, l, lc, 1, 1.0 / moments[1], 0.5 * h)
        _axis_rotation(q, l, lc, 0, 1.0 / moments[0], 0.5 * h)


@njit(cache=True)
def _turn_frame(q, rate, h):
    """In place: q <- exp(rate h / 2) q, the exact flow of q' = (0, rate) q / 2 (rate inertial, constant)."""
    norm = math.sqrt(rate[0] ** 2 + rate[1] ** 2 + rate[2] ** 2)
    if norm == 0.0:
        return
    s = math.sin(0.5 * norm * h) / norm
    b0, b1, b2, b3 = math.cos(0.5 * norm * h), s * rate[0], s * rate[1], s * rate[2]
    a0, a1, a2, a3 = q[0], q[1], q[2], q[3]
    q[0] = b0 * a0 - b1 * a1 - b2 * a2 - b3 * a3
    q[1] = b0 * a1 + b1 * a0 + b2 * a3 - b3 * a2
    q[2] = b0 * a2 - b1 * a3 + b2 * a0 + b3 * a1
    q[3] = b0 * a3 + b1 * a2 - b2 * a1 + b3 * a0


@template("torque", "frame_rate")
def split_loop(params, moments, t, q, l, lc, n_torque, t_out, y_out, h, gammas, symmetric, axes, max_steps):
    """Fixed steps of at most h landing on every output time (either direction), from time t.

    The state q, l (with its compensation lc) and the last torque n_torque are
    updated in place, so that a caller can resume exactly.  Returns
    (n_done, steps, nfev, t).
    """
    s, i, j = axes[0], axes[1], axes[2]
    y = np.empty(7)
    for m in range(4):
        y[m] = q[m]
    for m in range(3):
        y[4 + m] = l[m] / moments[m]
    nfev, steps = 0, 0
    for k in range(t_out.shape[0]):
        span = t_out[k] - t
        # an output a rounding error past k steps takes k steps, not k + 1
        n_sub = int(np.ceil(abs(span) / h - 1e-9)) if span != 0.0 else 0
        dt = span / n_sub if n_sub > 0 else 0.0
        for _ in range(n_sub):
            for g in gammas:
                sub = g * dt
                for m in range(3):
                    _add(l, lc, m, 0.5 * sub * n_torque[m])
                _free_flow(q, l, lc, moments, sub, symmetric, s, i, j)
                _turn_frame(q, frame_rate(t + 0.5 * sub, y, params), sub)
                t += sub
                for m in range(4):
                    y[m] = q[m]
                for m in range(3):
                    y[4 + m] = l[m] / moments[m]
                put(n_torque, torque(t, y, params))
                nfev += 1
                for m in range(3):
                    _add(l, lc, m, 0.5 * sub * n_torque[m])
            steps += 1
            if steps > max_steps or not (np.all(np.isfinite(l)) and np.all(np.isfinite(q))):
                return k, steps, nfev, t
        t = t_out[k]
        q /= math.sqrt(q[0] ** 2 + q[1] ** 2 + q[2] ** 2 + q[3] ** 2)   # rotations keep |q| = 1 to rounding
        y_out[k, :4] = q
        for m in range(3):
            y_out[k, 4 + m] = (l[m] - lc[m]) / moments[m]
    return t_out.shape[0], steps, nfev, t


def symmetric_axes(moments):
    """(s, i, j): s the axis whose companions have the closest moments (A=B -> z, B=C -> x)."""
    a, b, c = moments
    return (2, 0, 1) if b - a <= c - b else (0, 2, 1)


class Strang(Integrator):
    """Kick-drift-kick splitting, order 2; options ``step`` (days) and ``free_flow``."""

    name, order, kind = "strang", 2, "structure-preserving"
    options = {"step": STEP(1.0), "free_flow": FREE_FLOW, "max_steps": MAX_STEPS}
    gammas = np.array([1.0])

    def supports(self, system):
        return system.torque is not None and system.layout.size == 7

    def solve(self, system, t_out):
        t_out = self._check_times(system, t_out)
        h = float(self.settings["step"])
        if not h > 0:
            raise InputError("step", h, "a positive step in days")
        flow = self.settings["free_flow"]
        if flow not in FREE_FLOWS:
            raise InputError("free_flow", flow, f"one of {list(FREE_FLOWS)}")
        moments = np.asarray(system.moments, dtype=float)
        loop = link(split_loop, torque=system.torque, frame_rate=system.frame_rate)
        t0, q, l, lc = float(system.t0), system.y0[:4].copy(), moments * system.y0[4:7], np.zeros(3)
        n_torque = system.torque(t0, system.y0[:7], system.params)     # compiles outside the timing
        fixed = (h, self.gammas, flow == "symmetric", np.array(symmetric_axes(moments)))
        max_steps = int(self.settings["max_steps"])
        y = np.empty((t_out.size, 7))
        loop(system.params, moments, t0, q, l, lc, n_torque, t_out[:0], y[:0], *fixed, max_steps)
        start = time.perf_counter()
        t, nfev, steps, n_done = t0, 1, 0, 0
        with progress(self.label, t0, float(t_out[-1])) as advance_to:
            for part in output_chunks(t_out.size):
                n, more, calls, t = loop(system.params, moments, t, q, l, lc, n_torque, t_out[part],
                                         y[part], *fixed, max_steps - steps)
                n_done, steps, nfev = n_done + n, steps + more, nfev + calls
                if n < part.stop - part.start:
                    break
                advance_to(t)
        t_fail = t
        wall = time.perf_counter() - start
        solution = Trajectory(t_out[:n_done], y[:n_done], self.name, nfev, steps, wall, dict(self.settings),
                            system.layout)
        if n_done < t_out.size:
            reason = "exceeded max_steps" if steps > self.settings["max_steps"] else "state became non-finite"
            err = IntegrationError(f"{self.name}: {reason}", t_fail, y[n_done - 1] if n_done else system.y0,
                                   "Raise integrator.max_steps." if steps > self.settings["max_steps"] else
                                   "Reduce integrator.step, or use an adaptive method (dop853) to find the difficulty.")
            err.partial = solution
            raise err
        return solution


def _triple_jump():
    g1 = 1.0 / (2.0 - 2.0 ** (1.0 / 3.0))
    return np.array([g1, 1.0 - 2.0 * g1, g1])


def _suzuki():
    g1 = 1.0 / (4.0 - 4.0 ** (1.0 / 3.0))
    return np.array([g1, g1, 1.0 - 4.0 * g1, g1, g1])


class Yoshida4(Strang):
    """Strang composed as a triple jump (Yoshida 1990), order 4, three torque calls per step."""

    name, order = "yoshida4", 4
    gammas = _triple_jump()


class Suzuki4(Strang):
    """Strang composed in five stages (Suzuki 1990), order 4, five torque calls per step."""

    name, order = "suzuki4", 4
    gammas = _suzuki()
