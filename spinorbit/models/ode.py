"""What an integrator integrates: an equation with its state's layout."""
import dataclasses
from dataclasses import dataclass, field

import numpy as np

from ..base.layout import Layout


@dataclass
class Ode:
    """What an integrator integrates: y' = rhs(t, y, params) from (t0, y0), the state laid out by ``layout``.

    A System is one (every model); a bare Ode serves an equation that is not a model of bodies (DE421's core
    carried under its prescribed mantle)."""

    rhs: object
    params: tuple
    t0: float
    y0: np.ndarray
    layout: Layout
    name: str = "ode"
    meta: dict = field(default_factory=dict)
    torque: object = None

    def with_start(self, t0, y0):
        return dataclasses.replace(self, t0=float(t0), y0=self.layout.normalise_state(y0))
