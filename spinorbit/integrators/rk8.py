"""Compiled fixed-step explicit Runge-Kutta of order 8 (the DOP853 tableau, Hairer & Wanner).

The whole loop runs in numba: the right-hand side is a numba function
``rhs(t, y, p)`` and is called 12 times per step, with no Python in between.
Use it where the step can be chosen once (smooth forcing); it reaches the
rounding floor (about 1e-12 relative in the attitude) at h ~ 1 d for the Moon.

The step does not depend on the output cadence: where outputs are closer
than the step, they come from DOP853's 7th-order continuous extension (four
more rhs calls in each step that holds an output, Hairer, Norsett & Wanner
II.6, the first of which, at the step's end, is the next step's first stage:
three more in all); otherwise the step is shortened slightly to land on every output.
A span that ends before its start is integrated backward with the step negated.
"""
import sys
import time

import numpy as np

from ..base.errors import InputError, IntegrationError
from ..base.layout import Layout
from ..base.linker import free, link, template
from ..base.progress import progress, stage
from . import dop853_tableau as dop853
from .base import Integrator, Trajectory, normalised, output_chunks
from .options import MAX_STEPS, STEP

rhs, put = free("rhs", "put")    # bound by link(): the right-hand side, rotations.put


@template("rhs", "put")
def rk_step(params, t, y, dt, a, b, c, k, ys, first):
    """One explicit Runge-Kutta step of size dt; fills the stages k from stage ``first`` (the stages before it are
    already in k); returns the new state."""
    n_stages, dim = b.shape[0], y.shape[0]
    for s in range(first, n_stages):
        for m in range(dim):
            ys[m] = y[m]
        for j in range(s):
            if a[s, j] != 0.0:
                w = dt * a[s, j]
                for m in range(dim):
                    ys[m] += w * k[j, m]
        put(k[s], rhs(t + c[s] * dt, ys, params))
    y_new = y.copy()
    for s in range(n_stages):
        if b[s] != 0.0:
            w = dt * b[s]
            for m in range(dim):
                y_new[m] += w * k[s, m]
    return y_new


@template("rk_step", "put")
def rk_fixed(params, t0, y0, t_out, h, a, b, c, max_steps):
    """Integrate with steps of at most |h|, landing exactly on every output time (either direction).

    Returns (y_out, n_done, steps, t_fail): n_done < len(t_out) when the state
    became non-finite or ``max_steps`` steps were taken (then t_fail is where).
    """
    dim = y0.shape[0]
    y_out = np.empty((t_out.shape[0], dim))
    k = np.empty((b.shape[0], dim))
    ys = np.empty(dim)
    y = y0.copy()
    t = t0
    steps = 0
    for i in range(t_out.shape[0]):
        span = t_out[i] - t
        # an output a rounding error past k steps takes k steps, not k + 1
        n_sub = int(np.ceil(abs(span) / abs(h) - 1e-9)) if span != 0.0 else 0
        dt = span / n_sub if n_sub > 0 else 0.0
        for _ in range(n_sub):
            if steps >= max_steps:
                return y_out, i, steps, t
            y = rk_step(params, t, y, dt, a, b, c, k, ys, 0)
            t += dt
            steps += 1
            if not np.all(np.isfinite(y)):
                return y_out, i, steps, t
        put(y_out[i], y)
        t = t_out[i]
    return y_out, t_out.shape[0], steps, t


@template("rhs", "rk_step", "put")
def rk8_dense(params, t_origin, y, steps, i, y_out, t_out, h, a, b, c, a_ext, c_ext, d, max_steps, k, known):
    """Steps of h (signed; the last one shortened to end on t_out[-1]) on the grid t_origin + steps h,
    from state ``y`` after ``steps`` steps, filling ``y_out`` from index i; outputs inside a step from
    the DOP853 continuous extension (order 7).  Stops after ``max_steps`` steps in all, so that a
    caller can resume exactly where it stopped.

    ``k`` (n_stages + 4, dim) holds the stages; ``known``: k[0] already holds rhs(t, y), the first stage of
    the next step.  A step with outputs computes rhs(t_new, y_new) for the extension, and that is the next
    step's first stage (its c is 0): the next step takes it instead of computing it again (first same as last).
    Returns (i, steps, t, y, rhs calls beyond n_stages per step, ok, known)."""
    dim = y.shape[0]
    n_stages = b.shape[0]
    ys = np.empty(dim)
    f = np.empty((7, dim))
    t = t_origin + steps * h
    extra = 0
    while i < t_out.shape[0] and (t_out[i] - t) * h <= 0.0:
        put(y_out[i], y)
        i += 1
    while i < t_out.shape[0] and steps < max_steps:
        dt = h if abs(h) < abs(t_out[-1] - t) else t_out[-1] - t
        y_new = rk_step(params, t, y, dt, a, b, c, k, ys, 1 if known else 0)
        if known:
            extra -= 1
        known = False
        steps += 1
        if not np.all(np.isfinite(y_new)):
            return i, steps, t, y, extra, False, False
        t_new = t + dt if dt != h else t_origin + steps * h     # no drift of the step grid
        if (t_out[i] - t_new) * h <= 0.0:
            extra += 4
            put(k[n_stages], rhs(t_new, y_new, params))
            for s in range(3):                           # the three extra stages
                for m in range(dim):
                    ys[m] = y[m]
                for j in range(n_stages + 1 + s):
                    if a_ext[s, j] != 0.0:
                        for m in range(dim):
                            ys[m] += dt * a_ext[s, j] * k[j, m]
                put(k[n_stages + 1 + s], rhs(t + c_ext[s] * dt, ys, params))
            for m in range(dim):
                delta = y_new[m] - y[m]
                f[0, m] = delta
                f[1, m] = dt * k[0, m] - delta
                f[2, m] = 2.0 * delta - dt * (k[n_stages, m] + k[0, m])
            for r in range(4):
                f[3 + r] = 0.0
                for j in range(n_stages + 4):
                    if d[r, j] != 0.0:
                        for m in range(dim):
                            f[3 + r, m] += dt * d[r, j] * k[j, m]
            while i < t_out.shape[0] and (t_out[i] - t_new) * h <= 0.0:
                x = (t_out[i] - t) / dt
                for m in range(dim):
                    value = 0.0
                    for r in range(6, -1, -1):           # Horner form of scipy's Dop853DenseOutput
                        value += f[r, m]
                        value *= x if (6 - r) % 2 == 0 else 1.0 - x
                    y_out[i, m] = y[m] + value
                i += 1
            put(k[0], k[n_stages])
            known = True
        y, t = y_new, t_new
    return i, steps, t, y, extra, True, known


def _landing_shortens(t_out, t0, h):
    """True when landing on every output would take over 10 % more steps than a uniform grid of h."""
    spans = np.abs(np.diff(np.concatenate([[t0], t_out])))
    landing = np.sum(np.ceil(spans / abs(h) - 1e-9))
    return bool(landing > 1.1 * np.ceil(np.sum(spans) / abs(h) - 1e-9))


def fixed_step(rhs, params, t0, y0, t_out, step, max_steps=10**9):
    """States (len(t_out), dim) of y' = rhs(t, y, params) from (t0, y0), any state (no quaternion renormalised):
    the RK8 with steps <= ``step`` landing on every output; IntegrationError if the state becomes non-finite or
    max_steps runs out."""
    y0 = np.ascontiguousarray(y0, dtype=float)
    ode = _Bare(rhs, params, float(t0), y0, Layout([("y", y0.size, "vector", "")]))
    integrator = RK8(step=step, max_steps=max_steps)
    integrator.label, integrator.lands = None, True
    return integrator.solve(ode, t_out).y


class _Bare:
    """An equation with no model behind it (what :func:`fixed_step` integrates)."""

    def __init__(self, rhs, params, t0, y0, layout):
        self.rhs, self.params, self.t0, self.y0, self.layout, self.name = rhs, params, t0, y0, layout, "ode"
        self.torque, self.meta = None, {}


class RK8(Integrator):
    """Fixed-step 8th-order explicit Runge-Kutta, compiled; option ``step`` (time units, days).

    The one fixed-step driver: the compiled loop runs in chunks (at most 200, ending on outputs, so that they
    depend only on the number of outputs) with the progress bar advanced and the checkpoint offered the
    outputs between them; a run resumed from a checkpoint continues from its last output and gives the same
    states, bit for bit, as one that was never interrupted.
    """

    name, order, kind = "rk8", 8, "fixed"
    options = {"step": STEP(1.0), "max_steps": MAX_STEPS}
    resumable = True
    lands = False               # True: land on every output even where dense output would take fewer steps
    # Butcher tableau (methods as data): the 12-stage 8th-order part of DOP853,
    # and its continuous extension (three more stages, interpolation matrix D).
    A = np.ascontiguousarray(dop853.A[:12, :12])
    B = np.ascontiguousarray(dop853.B)
    C = np.ascontiguousarray(dop853.C[:12])
    DENSE = (np.ascontiguousarray(dop853.A[13:16]), np.ascontiguousarray(dop853.C[13:16]),
             np.ascontiguousarray(dop853.D))

    def solve(self, system, t_out):
        from ..base import rotations

        t_out = self._check_times(system, t_out)
        h = float(self.settings["step"])
        if not h > 0:
            raise InputError("step", h, "a positive step in days")
        h = h if t_out[-1] >= system.t0 else -h
        with stage(None if self.label is None else f"{self.label}: compiling the integrator (once: cached after)"):
            step = link(rk_step, rhs=system.rhs, put=rotations.put)
            if self.DENSE is not None and not self.lands and _landing_shortens(t_out, system.t0, h):
                dense = link(rk8_dense, rhs=system.rhs, rk_step=step, put=rotations.put)
                run = _Dense(dense, self, system, t_out, h)
            else:
                run = _Landing(link(rk_fixed, rk_step=step, put=rotations.put), self, system, t_out, h)
        start = time.perf_counter()
        run.drive(self.label, self.checkpoint)
        wall = time.perf_counter() - start
        solution = Trajectory(t_out[:run.done], normalised(system, run.y_out[:run.done]), self.name,
                            run.steps * len(self.B) + run.extra, run.steps, wall, dict(self.settings), system.layout)
        if run.done < t_out.size:
            over = run.steps >= int(self.settings["max_steps"])
            err = IntegrationError(f"{self.name}: {'exceeded max_steps' if over else 'state became non-finite'}",
                                   run.t, run.y_out[run.done - 1] if run.done else system.y0,
                                   "Raise integrator.max_steps." if over else
                                   "Reduce integrator.step, or use an adaptive method (dop853) to find the difficulty.")
            err.partial = solution
            raise err
        return solution


class _CompiledRun:
    """One run of a compiled loop, advanced chunk by chunk (:meth:`drive`), with what it has done so far."""

    def __init__(self, loop, method, system, t_out, h):
        self.loop, self.system, self.t_out, self.h = loop, system, t_out, h
        self.tableau = (method.A, method.B, method.C)
        self.max_steps = int(method.settings["max_steps"])
        self.y_out = np.empty((t_out.size, system.y0.size))
        self.t, self.y, self.steps, self.done, self.extra, self.failed = float(system.t0), system.y0, 0, 0, 0, False
        self.compile()

    def drive(self, label, checkpoint):
        """Advance to the end (or a failure): progress between chunks, the checkpoint saved as it asks and when
        the run stops on an exception."""
        fingerprint = None
        if checkpoint is not None:
            fingerprint = self.fingerprint(checkpoint)
            stored = checkpoint.load(fingerprint)
            if stored is not None:
                self.restore(stored)
                print(f"resuming from {checkpoint.path} at output {self.done} of {self.t_out.size}", file=sys.stderr)
        saved, last_save = self.done, time.monotonic()
        with progress(label, self.t, float(self.t_out[-1])) as advance_to:
            try:
                while not self.failed and self.done < self.t_out.size:
                    _uninterrupted(self.advance)
                    advance_to(self.t)
                    if checkpoint is not None and time.monotonic() - last_save >= checkpoint.every_s:
                        if checkpoint.keep(fingerprint, self.y_out[:self.done]):
                            saved = self.done
                        last_save = time.monotonic()
                if checkpoint is not None and self.done > saved:     # whole: a scene's next run may be interrupted
                    if checkpoint.keep(fingerprint, self.y_out[:self.done]):
                        saved = self.done
            except BaseException:
                if checkpoint is not None and self.done > 0:
                    if self.done > saved and checkpoint.keep(fingerprint, self.y_out[:self.done]):
                        saved = self.done
                    if saved:
                        print(f"checkpoint: {saved} of {self.t_out.size} outputs in {checkpoint.path} "
                              "(continue with --resume)", file=sys.stderr)
                raise

    def fingerprint(self, checkpoint):
        s = self.system
        return checkpoint.fingerprint(s.rhs, s.params, s.t0, s.y0, self.t_out, abs(self.h))


class _Landing(_CompiledRun):
    """The loop that lands on every output (uniform sub-steps between outputs), resumed at outputs."""

    def compile(self):
        self.loop(self.system.params, self.t, self.y, self.t_out[:1], self.h, *self.tableau, 0)
        self.chunks, self.next_chunk = output_chunks(self.t_out.size), 0

    def advance(self):
        part = self.chunks[self.next_chunk]
        states, n, more, t_fail = self.loop(self.system.params, self.t, self.y, self.t_out[part], self.h,
                                            *self.tableau, self.max_steps - self.steps)
        self.y_out[part.start:part.start + n] = states[:n]
        self.steps, self.done = self.steps + more, self.done + n
        if n < part.stop - part.start:
            self.failed, self.t = True, t_fail
            return
        self.t, self.y, self.next_chunk = float(self.t_out[part.stop - 1]), states[-1], self.next_chunk + 1

    def restore(self, outputs):
        """Continue after the outputs a checkpoint holds (they end a chunk: chunks depend only on their number)."""
        k = len(outputs)
        self.y_out[:k] = outputs
        self.done, self.t, self.y = k, float(self.t_out[k - 1]), outputs[-1]
        self.next_chunk = next(i for i, part in enumerate(self.chunks) if part.start == k)


class _Dense(_CompiledRun):
    """The uniform-step loop with dense output, resumed every two-hundredth of the run (not checkpointed)."""

    def compile(self):
        self.tableau = (*self.tableau, *RK8.DENSE)
        self.k = np.empty((self.tableau[1].size + 4, self.y.size))
        self.known = False                  # k[0] holds rhs(t, y): the last step's extension computed it
        self.loop(self.system.params, self.t, self.y, 0, 0, self.y_out, self.t_out[:1], self.h, *self.tableau, 0,
                  self.k, False)
        self.t0 = self.t
        self.chunk = max(1, int(abs(self.t_out[-1] - self.t) / abs(self.h)) // 200)

    def advance(self):
        limit = min(self.steps + self.chunk, self.max_steps)
        self.done, self.steps, self.t, self.y, more, ok, self.known = self.loop(
            self.system.params, self.t0, self.y, self.steps, self.done, self.y_out, self.t_out, self.h, *self.tableau,
            limit, self.k, self.known)
        self.extra += more
        self.failed = not ok or (self.steps >= self.max_steps and self.done < self.t_out.size)

    def drive(self, label, checkpoint):
        super().drive(label, None)          # outputs closer than the step: checkpoints need landing on them


def _uninterrupted(advance):
    """advance(); an interrupt (Ctrl-C, SIGTERM) that numba wrapped in a SystemError is an interrupt again."""
    try:
        advance()
    except SystemError as exc:           # the handler ran in a Python callback of the compiled call
        if isinstance(exc.__cause__, KeyboardInterrupt):
            raise KeyboardInterrupt from None
        raise
