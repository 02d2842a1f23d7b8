"""The harmonic fit at fixed arguments against series built from known terms, and its refusals.

A series made of a quadratic and sinusoids of known amplitudes at known arguments is
fitted back exactly (to rounding); a term the span cannot separate, from the polynomial
or from a term kept before it, is not fitted and its reason names the span it needs:
half its period, or half the beat period (pi / |rate difference|).
"""
import math

import numpy as np
import pytest

from spinorbit.analysis.harmonics import fit_harmonics
from spinorbit.base.constants import JULIAN_CENTURY_D
from tests.units import arcsec, mas

# name -> (period d, phase at J2000 rad, sin amplitude, cos amplitude), amplitudes in rad
TERMS = {"18.6 yr": (6798.38, 2.18, -17.2 * arcsec, 0.003 * arcsec),
         "0.5 yr": (182.62, -0.4, -1.32 * arcsec, -0.0014 * arcsec),
         "13.66 d": (13.66, 1.1, -0.228 * arcsec, 0.0003 * arcsec)}
POLY = (0.01 * arcsec, 5038.0 * arcsec, -1.07 * arcsec)     # c0, c1 per century, c2 per century^2


def arguments(t, terms=TERMS):
    return {name: (2 * math.pi * t / period + phase, 2 * math.pi / period)
            for name, (period, phase, _, _) in terms.items()}


def series(t, terms=TERMS):
    big_t = t / JULIAN_CENTURY_D
    value = sum(c * big_t**k for k, c in enumerate(POLY))
    for (name, (a, _)), (_, _, s, c) in zip(arguments(t, terms).items(), terms.values()):
        value = value + s * np.sin(a) + c * np.cos(a)
    return value


def test_known_terms_are_recovered_over_a_century():
    t = np.arange(-18262.5, 18262.5, 2.0)
    fit = fit_harmonics(t, series(t), arguments(t))
    assert not fit.refused
    for name, (_, _, s, c) in TERMS.items():
        assert fit.sin[name] == pytest.approx(s, abs=1e-6 * mas)
        assert fit.cos[name] == pytest.approx(c, abs=1e-6 * mas)
    assert np.allclose(fit.poly, POLY, rtol=0, atol=1e-6 * mas)


def test_a_term_longer_than_twice_the_span_is_refused_with_the_span_it_needs():
    t = np.arange(0.0, 730.0, 0.5)                       # 2 yr: 18.6 yr needs 6798.38 / 2 d
    fit = fit_harmonics(t, series(t), arguments(t))
    assert fit.sin["18.6 yr"] is None and fit.cos["18.6 yr"] is None
    assert "needs a span of 3399 d, the run has 730 d (half its period)" == fit.refused["18.6 yr"]
    assert set(fit.refused) == {"18.6 yr"}
    assert fit.sin["13.66 d"] is not None


def test_two_terms_closer_than_the_span_resolves_keep_the_first():
    """177.84 d beats with 182.62 d in 6794 d: over 10 yr it is separated, over 5 yr it is not."""
    close = {**TERMS, "177.8 d": (177.84, 0.7, 0.15 * arcsec, 0.0)}
    need = math.pi / abs(2 * math.pi / 177.84 - 2 * math.pi / 182.62)
    for years, refused in ((10, False), (5, True)):
        t = np.arange(0.0, years * 365.25, 0.5)
        fit = fit_harmonics(t, series(t, close), arguments(t, close))
        assert (fit.sin["177.8 d"] is None) == refused
        if refused:
            assert fit.refused["177.8 d"].startswith(f"needs a span of {need:.0f} d")
            assert fit.refused["177.8 d"].endswith("(it beats with 0.5 yr)")
        else:
            assert fit.sin["177.8 d"] == pytest.approx(0.15 * arcsec, abs=1e-6 * mas)
    fit = fit_harmonics(t, series(t, close), arguments(t, close), separate=False)
    assert fit.sin["177.8 d"] is not None          # against the polynomial only: both kept
