"""The one interface every reference offers: ``reference(t_tdb_d) -> Comparable``.

A reference is anything a run is judged against: the JPL DE421 lunar orientation, the
IAU 2006/2000A pole (ERFA), a closed form of Euler's chapters 15-16.  It is called with
TDB days from J2000 and returns the quantities a scene compares, in internal units (the
unit in each name: ``pole_rad``, ``cip_x_rad``), with where they come from.
"""
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np


@dataclass(frozen=True)
class Comparable:
    """Reference values at the requested times and their provenance.

    ``values``: name -> array over the times (internal units, the unit in the name);
    ``provenance``: what produced them (model, data file or package and version, citation,
    valid span) -- written to the summary beside the comparison.
    """

    t_tdb_d: np.ndarray
    values: dict
    provenance: dict = field(default_factory=dict)

    def __getitem__(self, name):
        return self.values[name]


class Reference(Protocol):
    """A callable reference: ``name`` for reports, ``__call__(t_tdb_d) -> Comparable``."""

    name: str

    def __call__(self, t_tdb_d) -> Comparable: ...
