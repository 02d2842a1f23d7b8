"""rk8's dense output: a step with outputs computes rhs at its end for DOP853's continuous extension, and the
next step takes it as its first stage instead of computing it again: 15 rhs per step, not 16, same states."""
import math

import numpy as np
import pytest

from spinorbit.base import rotations
from spinorbit.base.linker import link
from spinorbit.base.rotations import quat_from_euler313
from spinorbit.integrators import simulate
from spinorbit.integrators.rk8 import RK8, rk8_dense, rk_step
from spinorbit.models.assemblies.idealised import under_point_masses
from spinorbit.orbits.analytic import CircularOrbits

STEP = 0.2


@pytest.fixture(scope="module")
def system():
    """An asymmetric body torqued by one point mass on an inclined circle."""
    orbit = CircularOrbits(("m",), gm=[0.5], radius=[1.0], rate=[1.0], inclination=[0.3])
    return under_point_masses(np.array([0.8, 1.0, 1.3]), orbit, quat_from_euler313(0.2, 0.5, 0.1), [0.3, -0.4, 1.2])


def run(system, t_out, h, steps_per_call, carry):
    """The compiled dense loop over t_out, called for ``steps_per_call`` steps at a time; ``carry``: the last
    step's end-point rhs is handed to the next call (as RK8 does between its chunks), else every call computes
    its first stage afresh.  Returns (states, steps, rhs calls)."""
    step = link(rk_step, rhs=system.rhs, put=rotations.put)
    loop = link(rk8_dense, rhs=system.rhs, rk_step=step, put=rotations.put)
    y_out, y, t0 = np.empty((t_out.size, system.y0.size)), system.y0, float(system.t0)
    k = np.empty((RK8.B.size + 4, y.size))
    i, steps, extra, known = 0, 0, 0, False
    while i < t_out.size:
        i, steps, _, y, more, ok, known = loop(system.params, t0, y, steps, i, y_out, t_out, h, RK8.A, RK8.B, RK8.C,
                                               *RK8.DENSE, steps + steps_per_call, k, known and carry)
        assert ok
        extra += more
    return y_out, steps, steps * RK8.B.size + extra


@pytest.mark.parametrize("direction", [1.0, -1.0])
def test_a_step_takes_its_first_stage_from_the_last_steps_extension_with_the_same_states(system, direction):
    """Outputs every 0.013 d with steps of 0.2 d (every step holds one): computing each step's first stage
    afresh, taking it from the step before (in one call, or carried across calls of one step each) give the
    same states bit for bit, and the reuse saves one rhs on every step but the first."""
    t_out = direction * np.arange(0.013, 60.0, 0.013)
    fresh, steps, fresh_rhs = run(system, t_out, direction * STEP, 1, carry=False)
    whole, whole_steps, whole_rhs = run(system, t_out, direction * STEP, 10**9, carry=True)
    pieces, _, pieces_rhs = run(system, t_out, direction * STEP, 1, carry=True)
    assert steps == whole_steps == math.ceil(60.0 / STEP - 1e-9)
    assert np.array_equal(whole, fresh) and np.array_equal(pieces, fresh)
    assert fresh_rhs == 16 * steps and whole_rhs == pieces_rhs == fresh_rhs - (steps - 1)


def test_simulate_reports_fifteen_rhs_per_dense_step_and_only_reuses_after_an_extension(system):
    """Through simulate(): a run whose every step holds an output costs 16 rhs on the first step and 15 on the
    others; where outputs thin out, only a step right after one holding outputs (which computed the extension)
    saves its first stage."""
    dense = simulate(system, np.arange(0.0, 60.0, 0.013), "rk8", {"step": STEP}, estimate_error=False)[0]
    assert dense.nfev == 16 + 15 * (dense.nsteps - 1)
    mixed_t = np.concatenate([np.arange(0.0, 20.0, 0.013), np.arange(20.0, 40.0, 0.5), np.arange(40.0, 60.0, 0.013)])
    mixed = simulate(system, mixed_t, "rk8", {"step": STEP}, estimate_error=False)[0]
    held = np.unique(np.ceil(mixed_t[1:] / STEP - 1e-9))       # the steps (numbered from 1) that hold outputs
    assert 0 < held.size < mixed.nsteps == dense.nsteps
    reused = np.sum(held < mixed.nsteps)                      # the step right after each of them
    assert mixed.nfev == 12 * mixed.nsteps + 4 * held.size - reused
