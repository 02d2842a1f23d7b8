"""coupled_conservation's comparison on invariants that drift as a closed form says."""
import numpy as np
import pytest

from spinorbit.comparisons import conservation

RATE_E, RATE_L, TURN = 1e-12, 2e-12, 1e-10       # per day: E's and |L|'s relative drift, L's turn (rad)


class Drifting:
    """A System's invariants that drift linearly: E, |L|, and L turned about y."""

    def invariants(self, y, t):
        energy = -2.0 * (1 + RATE_E * t)
        big_l = 3.0 * (1 + RATE_L * t)[:, None] * np.column_stack([np.sin(TURN * t), 0 * t, np.cos(TURN * t)])
        return energy, big_l


class Solution:
    y = None


def test_the_drifts_and_their_rates_per_century_are_the_closed_forms():
    t = np.linspace(0.0, 20 * 365.25, 201)
    change = conservation.changes(Drifting(), Solution(), t)
    comparison, not_measured = conservation.metrics(change, t[-1], 1.0, 10 * 365.25)
    grown, turned = 1 + RATE_L * t[-1], TURN * t[-1]
    assert comparison[conservation.ENERGY_REL_DRIFT] == pytest.approx(RATE_E * t[-1], rel=1e-6)
    assert comparison[conservation.L_NORM_REL_DRIFT] == pytest.approx(RATE_L * t[-1], rel=1e-6)
    assert comparison[conservation.L_VECTOR_REL_DRIFT] == pytest.approx(
        np.sqrt((grown - 1) ** 2 + 4 * grown * np.sin(turned / 2) ** 2), rel=1e-6)
    assert comparison[conservation.per_century(conservation.ENERGY_REL_DRIFT)] == pytest.approx(
        RATE_E * 36525.0, rel=1e-6)
    assert comparison[conservation.PASSED] is True and not not_measured


def test_a_drift_beyond_the_tolerance_fails_and_a_short_span_is_not_judged():
    t = np.linspace(0.0, 20 * 365.25, 201)
    change = conservation.changes(Drifting(), Solution(), t)
    assert conservation.metrics(change, t[-1], RATE_E * 36525.0 / 2, 10 * 365.25)[0][conservation.PASSED] is False
    short, why = conservation.metrics(change, t[-1], 1.0, 30 * 365.25)
    assert short[conservation.PASSED] is None and f"comparison.{conservation.PASSED}" in why
