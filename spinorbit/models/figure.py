"""A body of a System and its figure: the inertia the torques act with, its gravity field beyond degree 2.

Units: one inertia unit for every System, G I (km^5/d^2), so that torques are G times the physical ones
(km^5/d^4), forces G m a (km^4/d^4) and the accelerations they give F / GM (km/d^2).  A System that only turns
(no orbit in its state) may give moments in any unit: only their ratios enter Euler's equations.
"""
from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class Field:
    """The gravity field of degrees ``n_min``..``n_max``: unnormalised C_nm, S_nm (C_n0 = -J_n) at ``radius_km``."""

    radius_km: float
    c_nm: np.ndarray
    s_nm: np.ndarray
    n_min: int = 3

    @property
    def n_max(self):
        return self.c_nm.shape[0] - 1


@dataclass(frozen=True)
class Figure:
    """Principal moments (A, B, C), G-scaled, in body axes x, y, z; the field beyond degree 2 (or None); the
    relative rate (per day) at which the anisotropy changes (the Earth's secular J2: dJ2/dt / J2)."""

    moments: np.ndarray
    field: Field | None = None
    anisotropy_rate_per_d: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "moments", np.asarray(self.moments, dtype=float))

    @property
    def c_minus_a(self):
        """C - (A + B)/2: G M J2 R^2 of the body as an oblate attractor."""
        return float(self.moments[2] - 0.5 * (self.moments[0] + self.moments[1]))


@dataclass(frozen=True)
class Body:
    """A member of a System: its GM (km^3/d^2), figure and rotator (None: a point mass that does not turn)."""

    name: str
    gm: float = 0.0
    figure: Figure | None = None
    rotator: object = field(default=None)
