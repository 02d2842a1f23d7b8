"""Least-squares fits of periodic terms at fixed arguments beside a polynomial in time.

Layer 2 (numpy).  One fit serves the Moon's libration terms, the Earth's precession and
nutation, and the non-rigid decomposition.  The arguments are an input (phases in rad,
rates in rad/d): ``references.arguments`` computes the fundamental ones once, with ERFA.
A term the span cannot separate (``spans.resolvable``) is not fitted: its coefficients
are None and ``refused`` says which span it needs.
"""
from dataclasses import dataclass

import numpy as np

from ..base.constants import JULIAN_CENTURY_D
from .spans import refusals


@dataclass(frozen=True)
class HarmonicFit:
    """``poly``: c_k of ((t - origin) / Julian century)^k; ``sin``, ``cos``: name -> coefficient of the
    sine and cosine of the argument (None if not fitted); ``refused``: name -> reason; units of the data."""

    poly: list
    sin: dict
    cos: dict
    refused: dict


def fit_harmonics(t_tdb_d, values, arguments, degree=2, origin_d=0.0, separate=True):
    """Fit values(t) = sum_k c_k T^k + sum_j (s_j sin a_j + c_j cos a_j), T = (t - origin_d) / century.

    ``arguments``: name -> (phase (n,) rad, rate rad/d), in order of precedence: a term is kept only if
    it beats by half a cycle over the span against the polynomial and against every term kept before it
    (against the polynomial only with ``separate=False``: spans.resolvable).
    """
    t = np.asarray(t_tdb_d, dtype=float)
    span = float(np.ptp(t))
    names = list(arguments)
    refused = refusals(names, [arguments[name][1] for name in names], span, separate)
    kept = [name for name in names if name not in refused]
    big_t = (t - origin_d) / JULIAN_CENTURY_D
    phases = [np.asarray(arguments[name][0]) for name in kept]
    design = np.column_stack([big_t**k for k in range(degree + 1)]
                             + [np.sin(a) for a in phases] + [np.cos(a) for a in phases])
    coef = np.linalg.lstsq(design, np.asarray(values, dtype=float), rcond=None)[0]
    n, p = len(kept), degree + 1
    sin, cos = dict(zip(kept, coef[p:p + n].tolist())), dict(zip(kept, coef[p + n:].tolist()))
    return HarmonicFit(poly=coef[:p].tolist(), sin={name: sin.get(name) for name in names},
                       cos={name: cos.get(name) for name in names}, refused=refused)
