"""Compiled fixed-step classical Runge-Kutta of order 4 (Kutta 1901): the cheap baseline.

Same compiled loop as rk8 (``rk8.rk_fixed``) with the classical tableau; four
right-hand-side calls per step.
"""
import numpy as np

from .rk8 import RK8


class RK4(RK8):
    """Fixed-step classical 4th-order Runge-Kutta, compiled; option ``step`` (days)."""

    name, order = "rk4", 4
    A = np.array([[0.0, 0.0, 0.0, 0.0], [0.5, 0.0, 0.0, 0.0], [0.0, 0.5, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]])
    B = np.array([1.0, 2.0, 2.0, 1.0]) / 6.0
    C = np.array([0.0, 0.5, 0.5, 1.0])
    DENSE = None          # no continuous extension: steps land on the outputs
