"""Piecewise Chebyshev series on a uniform grid of segments: what a continuous solution is made of.

Segment k covers [origin + k L, origin + (k + 1) L]; on it each component is sum_j c_j T_j(x), x = 2 (t - mid) / L
in [-1, 1] (the layout of SPICE's type-2 records, NAIF's SPK and PCK Required Reading).  A series of degree n is
fitted by interpolation at the n + 1 Chebyshev points of the first kind, cos(pi (j + 1/2) / (n + 1)) (the roots of
T_(n+1)), where its error is near the best polynomial's (Trefethen, Approximation Theory and Approximation
Practice, ch. 11, 16); that error, f^(n+1)(xi) T_(n+1)(x) / (2^n (n + 1)!), peaks at T_(n+1)'s n + 2 extrema,
cos(pi j / (n + 1)), between the roots and at the ends (the middle among them for an odd degree): the fit's
error is measured there.
"""
from dataclasses import dataclass

import numpy as np

from ..base.errors import InputError


def first_kind(degree):
    """The n + 1 interpolation points in [-1, 1], descending."""
    return np.cos(np.pi * (np.arange(degree + 1) + 0.5) / (degree + 1))


def extrema(degree):
    """The n + 2 extrema of T_(n+1) in [-1, 1] (between the first kind's points, the ends included), descending."""
    return np.cos(np.pi * np.arange(degree + 2) / (degree + 1))


def interpolating(values):
    """Coefficients (..., n + 1) of the series through ``values`` (..., n + 1) at the first-kind points
    (the discrete cosine transform of the samples)."""
    n = values.shape[-1]
    j = np.arange(n)
    basis = np.cos(np.pi * np.outer(j, j + 0.5) / n) * (2.0 / n)
    basis[0] /= 2.0
    return values @ basis.T


def interpolating_at(values, x):
    """Coefficients (count, components, n + 1) of the series through ``values`` (count, components, n + 1) at
    the normalised points ``x`` (count, n + 1) where they were sampled: the first-kind points as the node times,
    rounded to doubles, fall (far from J2000 a day count's rounding, 1.8e-12 d in 1969, moves Mercury by 4 mm)."""
    vander = np.polynomial.chebyshev.chebvander(x, values.shape[-1] - 1)          # (count, n + 1, n + 1)
    return np.linalg.solve(vander, values.transpose(0, 2, 1)).transpose(0, 2, 1)


ROUNDING = 1e-9               # of a segment: what a span's end or a time may differ by through rounding
EVALUATED_AT_ONCE = 512        # points whose segments' coefficients are gathered together (a few hundred kB)


@dataclass
class Segments:
    """Segments ``first`` .. ``first + count - 1`` of length ``length_d`` on the grid from ``origin_d``;
    ``coefficients`` (count, components, degree + 1)."""

    origin_d: float
    length_d: float
    first: int
    coefficients: np.ndarray

    @property
    def degree(self):
        return self.coefficients.shape[2] - 1

    @property
    def span(self):
        """(start, end) TDB days."""
        return (self.origin_d + self.first * self.length_d,
                self.origin_d + (self.first + len(self.coefficients)) * self.length_d)

    def covers(self, t_start, t_end):
        """Whether [t_start, t_end] lies in the span, give or take ROUNDING of a segment: the span's ends are sums of
        segment lengths, a run's outputs sums of steps, each rounded (no more: never an extrapolation)."""
        lo, hi = self.span
        slack = ROUNDING * self.length_d
        return lo - slack <= min(t_start, t_end) and max(t_start, t_end) <= hi + slack

    def evaluate(self, t):
        """Values (n, components) at TDB days ``t`` (n,); InputError outside the span (no extrapolation)."""
        t = np.asarray(t, dtype=float)
        if t.size and not self.covers(t.min(), t.max()):
            raise InputError("t", f"{t.min():.6g}..{t.max():.6g} TDB days",
                             f"times inside the solution's span {self.span[0]:.6g}..{self.span[1]:.6g}")
        k = np.clip(np.floor((t - self.origin_d) / self.length_d).astype(int), self.first,
                    self.first + len(self.coefficients) - 1)
        mid = self.origin_d + (k + 0.5) * self.length_d
        basis = np.polynomial.chebyshev.chebvander(2.0 * (t - mid) / self.length_d, self.degree)[:, :, None]
        out = np.empty((t.size, self.coefficients.shape[1]))
        for lo in range(0, t.size, EVALUATED_AT_ONCE):          # each point's segment gathered a block at a time
            block = slice(lo, lo + EVALUATED_AT_ONCE)
            out[block] = np.matmul(self.coefficients[k[block] - self.first], basis[block])[:, :, 0]
        return out

    def at_normalised(self, x):
        """Values (count, len(x[k]), components): segment k at its own normalised points ``x[k]``."""
        vander = np.polynomial.chebyshev.chebvander(np.asarray(x, dtype=float), self.degree)
        return np.einsum("kcn,kpn->kpc", self.coefficients, vander)

    def normalised(self, t, first):
        """The normalised points x (count, n + 1) of times ``t`` (count, n + 1) in segments first, first + 1, ..."""
        mids = self.origin_d + (np.arange(first, first + len(t)) + 0.5) * self.length_d
        return 2.0 * (t - mids[:, None]) / self.length_d

    def nodes(self, first, count):
        """(interpolation times (count, n + 1), check times (count, n + 2)) of segments first..first+count-1."""
        mids = self.origin_d + (np.arange(first, first + count) + 0.5) * self.length_d
        half = self.length_d / 2.0
        return mids[:, None] + half * first_kind(self.degree), mids[:, None] + half * extrema(self.degree)

    def window(self, t_start, t_end):
        """The segments covering [t_start, t_end] (inside the span): whole segments, none beyond them."""
        if not self.covers(t_start, t_end):
            raise InputError("span", f"{t_start:.6g}..{t_end:.6g} TDB days",
                             f"a span inside the solution's {self.span[0]:.6g}..{self.span[1]:.6g}")
        first, count = grid_indices(self.origin_d, self.length_d, t_start, t_end)
        return Segments(self.origin_d, self.length_d, first,
                        self.coefficients[first - self.first:first - self.first + count])

    def joined(self, other):
        """These segments and ``other`` (the same grid, adjacent before or after) as one."""
        if (other.origin_d, other.length_d, other.degree) != (self.origin_d, self.length_d, self.degree):
            raise InputError("segments", "another grid", "segments on the same grid and degree")
        before, after = (other, self) if other.first < self.first else (self, other)
        if before.first + len(before.coefficients) != after.first:
            raise InputError("segments", f"from {other.first}", f"segments adjacent to {self.first}..")
        return Segments(self.origin_d, self.length_d, before.first,
                        np.concatenate([before.coefficients, after.coefficients]))


def fitted(origin_d, length_d, first, values):
    """Segments from ``values`` (count, components, degree + 1) at the first-kind points of each."""
    return Segments(origin_d, length_d, first, interpolating(values))


def grid_indices(origin_d, length_d, t_start, t_end):
    """(first, count): the segments of the grid that cover [t_start, t_end]."""
    lo = int(np.floor((min(t_start, t_end) - origin_d) / length_d + ROUNDING))
    hi = int(np.ceil((max(t_start, t_end) - origin_d) / length_d - ROUNDING))
    return lo, max(hi - lo, 1)


@dataclass(frozen=True)
class Grid:
    """Segments of ``length_d`` days, series of ``degree``, on the grid from ``origin_d`` (TDB days)."""

    origin_d: float
    length_d: float
    degree: int

    def bounds(self, lo, hi):
        """[lo, hi] rounded out to the grid's segment ends."""
        first, count = grid_indices(self.origin_d, self.length_d, lo, hi)
        return self.origin_d + first * self.length_d, self.origin_d + (first + count) * self.length_d
