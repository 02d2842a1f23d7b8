"""The state vector of a System as named slices: which part is whose, and what kind of quantity it is.

Every System lays its state out from its bodies: a body in the state contributes its position and velocity
(``earth_moon.r``, ``.v``: km, km/d, ICRF), a rotator its attitude and rates (``moon.q``, ``moon.omega``,
``moon.omega_core``, ``earth.spin``).  A slice's ``kind`` is what an integrator must know about it:
``"quaternion"`` (a unit quaternion, renormalised at the outputs) or ``"vector"``; ``unit`` says the rest.
"""
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class Slice:
    """Components [start, stop) of the state: ``name`` (``<body>.<part>``), kind and unit."""

    name: str
    start: int
    stop: int
    kind: str = "vector"
    unit: str = ""

    @property
    def index(self):
        return slice(self.start, self.stop)


class Layout:
    """The ordered slices of a state vector; ``layout["moon.q"]`` is a Python slice of it."""

    def __init__(self, parts):
        """parts: (name, size, kind, unit) in state order."""
        self.slices, start = [], 0
        for name, size, kind, unit in parts:
            self.slices.append(Slice(name, start, start + size, kind, unit))
            start += size
        self.size = start
        self._by_name = {s.name: s for s in self.slices}

    def __getitem__(self, name):
        return self._by_name[name].index

    def __contains__(self, name):
        return name in self._by_name

    @property
    def names(self):
        return [s.name for s in self.slices]

    @property
    def quaternions(self):
        """The quaternion slices (renormalised at every output)."""
        return [s.index for s in self.slices if s.kind == "quaternion"]

    def pack(self, parts):
        """The state vector from its named parts ({"moon.q": ..., "moon.omega": ...}); every slice must be
        given; quaternions are normalised."""
        missing = [s.name for s in self.slices if s.name not in parts]
        extra = sorted(set(parts) - set(self._by_name))
        if missing or extra:
            raise KeyError(f"state parts: missing {missing}, unknown {extra}; the layout is {self.names}")
        y = np.empty(self.size)
        for s in self.slices:
            value = np.asarray(parts[s.name], dtype=float).reshape(s.stop - s.start)
            y[s.index] = value
        return self.normalise_state(y)

    def normalise(self, states):
        """A copy of states (n, size) with every quaternion slice made unit."""
        states = np.array(states, dtype=float)
        for index in self.quaternions:
            states[:, index] /= np.linalg.norm(states[:, index], axis=1, keepdims=True)
        return states

    def normalise_state(self, y):
        """A copy of one state (size,) with every quaternion slice made unit."""
        y = np.array(y, dtype=float)
        for index in self.quaternions:
            y[index] /= np.linalg.norm(y[index])
        return y

    def split(self, states):
        """{slice name: the slice of states (..., size)}."""
        states = np.asarray(states)
        return {s.name: states[..., s.index] for s in self.slices}

    def __repr__(self):
        return "Layout(" + ", ".join(f"{s.name}[{s.start}:{s.stop}]" for s in self.slices) + ")"
