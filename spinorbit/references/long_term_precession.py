"""ERFA's long-term precession (Vondrak, Capitaine & Wallace 2011, A&A 534, A22; corrigendum 2012): the mean
equator's and the ecliptic's poles in the GCRS (ICRS axes) over +-200 kyr.

Its accuracy, as its authors give it: "within 100 microarcseconds during the 20th and 21st centuries ... a few
arcseconds throughout the historical period, worsening to a few tenths of a degree at the end of the
+-200,000 year time span".  Times TDB days from J2000, passed to ERFA as TT Julian epochs (they differ by
< 2 ms).
"""
import numpy as np

from ..base.errors import InputError
from .base import Comparable

SPAN_YR = 200_000.0


class LongTermPrecession:
    """A ``references.base.Reference`` with values ``equator_pole`` and ``ecliptic_pole`` (k, 3), unit
    vectors in ICRS axes (``erfa.ltpb``'s and ``erfa.ltecm``'s third rows), and ``obliquity_rad`` between
    them."""

    name = "ERFA long-term precession (Vondrak et al. 2011)"

    def __call__(self, t_tdb_d):
        import erfa

        t = np.atleast_1d(np.asarray(t_tdb_d, dtype=float))
        epoch = 2000.0 + t / 365.25
        if np.abs(epoch - 2000.0).max() > SPAN_YR:
            kyr = (epoch - 2000.0) / 1e3
            raise InputError("t_out", f"{kyr.min():.6g} to {kyr.max():.6g} kyr",
                             f"times within +-{SPAN_YR / 1e3:g} kyr of J2000 (the model's span)")
        equator = np.array([erfa.ltpb(e)[2] for e in epoch])
        ecliptic = np.array([erfa.ltecm(e)[2] for e in epoch])
        obliquity = np.arccos(np.clip(np.sum(equator * ecliptic, axis=1), -1.0, 1.0))
        return Comparable(t, {"equator_pole": equator, "ecliptic_pole": ecliptic, "obliquity_rad": obliquity},
                          provenance())


def provenance():
    import erfa

    return {"name": "long-term precession: erfa.ltpb (equator), erfa.ltecm (ecliptic)",
            "data": f"pyerfa {erfa.__version__} (ERFA {erfa.version.erfa_version})",
            "citation": "Vondrak, Capitaine & Wallace 2011, A&A 534, A22; 2012, A&A 541, C1",
            "span": "+-200 kyr from J2000; a few arcseconds over the historical period"}
