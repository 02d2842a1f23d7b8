"""A term: one interaction acting on a body's figure, and the kernel that sums a model's terms.

Every term offers two compiled functions with one signature,

    torque(t, y, rot, inertia, r_icrf, gm, p) -> (3,)   body axes, [inertia unit] rad/d^2
    force(t, y, rot, inertia, r_icrf, gm, p)  -> (n, 3) ICRF, [inertia unit]/(km d^2)

with ``y`` the body's state, ``rot`` its body-to-ICRF matrix, ``inertia`` its current inertia
tensor (body axes), ``r_icrf`` (n, 3) km the attracting bodies relative to the body's centre,
``gm`` (n,) km^3/d^2 their GM, and ``p`` the term's own parameters.  ``force`` is the force
the figure exerts on each attracting body; the body's centre feels minus their sum.  Action
equals reaction: rot @ torque + sum_i r_i x force_i = 0 (the torque on an attracting body's
own figure, where it has one, is that term's ``reaction_torque``).  Forces in units of the
inertia per km turn into accelerations by multiplying by M R^2 / m_i (inertia in M R^2).
"""
from dataclasses import dataclass, field
from typing import Callable

import numpy as np
from numba import njit

from ..linker import link_source


@njit(cache=True, nogil=True)
def anisotropic(inertia):
    """I - I_zz 1: the same torques and forces (an isotropic part exerts none), without the
    cancellation of r x (I r) for a nearly spherical body (the subtraction is exact, Sterbenz)."""
    out = inertia.copy()
    for i in range(3):
        out[i, i] -= inertia[2, 2]
    return out


@dataclass(frozen=True)
class Term:
    """One named interaction with its compiled torque (and force) and its parameters."""

    name: str
    torque: Callable
    params: tuple
    force: Callable | None = None
    source: str = ""                   # the equation's citation


@dataclass(frozen=True)
class Context:
    """What terms are built against.

    ``body``: the figure's body (spinorbit.bodies); ``names``/``gm``: the attracting bodies in the
    order of the orbit source's positions and their GM (km^3/d^2); ``poles``: name -> pole table
    (grid [t0, h] TDB days, (m, 3) unit vectors ICRF) of attractors whose figure is oblate.
    """

    body: object
    names: tuple
    gm: np.ndarray
    poles: dict = field(default_factory=dict)

    def index(self, name, term):
        """Row of ``name`` in the positions; KeyError naming the term otherwise."""
        if name not in self.names:
            raise KeyError(f"term {term!r} needs {name!r} among the orbit's bodies, got {list(self.names)}")
        return self.names.index(name)


def fuse(terms):
    """(kernel, params): one compiled torque(t, y, rot, inertia, r_icrf, gm, params) summing the terms'
    torques, params = the tuple of each term's parameters.  Generated once per list of terms and
    cached on disk (spinorbit.linker): no Python runs per step."""
    lines = ["def fused_torque(t, y, rot, inertia, r_icrf, gm, params):", "    total = np.zeros(3)"]
    lines += [f"    total += term{k}(t, y, rot, inertia, r_icrf, gm, params[{k}])" for k in range(len(terms))]
    lines.append("    return total")
    kernel = link_source("fused_torque", "\n".join(lines) + "\n",
                         **{f"term{k}": term.torque for k, term in enumerate(terms)})
    return kernel, tuple(term.params for term in terms)


def total_force(terms, t, y, rot, inertia, r_icrf, gm):
    """Sum of the terms' forces on the attracting bodies (n, 3), ICRF (Python-level; for checks)."""
    total = np.zeros_like(np.asarray(r_icrf, dtype=float))
    for term in terms:
        if term.force is not None:
            total += term.force(t, y, rot, inertia, r_icrf, gm, term.params)
    return total
