"""A System: a model written as data -- bodies, how they move, what acts between them -- and what follows.

From the data the System derives its state layout (named slices, :mod:`~spinorbit.base.layout`), one
parameter record (``parameters``: name -> value, passed to the compiled functions as the tuple ``params``) and
its compiled functions, generated and cached on disk (:mod:`~spinorbit.models.generate`,
:mod:`spinorbit.base.linker`): ``rhs(t, y, params)`` always; ``torque(t, y, params)`` for a lone rigid body (what
splitting integrators kick with) and ``frame_rate(t, y, params)``, the rate of the frame its equations hold in
(what they turn its attitude by); ``energy`` and ``angular_momentum`` for a closed System.

    >>> system = System("free body", [Body("body", figure=Figure([2.0, 1.0, 2 / 3]), rotator=Rigid())],
    ...                 Centred("body"), [])                               # doctest: +SKIP
    >>> system.layout                                                        # doctest: +SKIP
    Layout(body.q[0:4], body.omega[4:7])
"""
import copy
import functools

import numpy as np

from ..base.layout import Layout
from ..base.linker import link_source
from .generate import angular_momentum_source, as_array, energy_source, frame_rate_source, rhs_source, torque_source
from .rotators import Gyroscopic, Rigid


class System:
    """``bodies``: Body list (spinorbit.models.figure); ``motion``: Centred or Pair (spinorbit.models.motion);
    ``interactions``: Interaction list (spinorbit.models.interactions); ``t0`` TDB days (or the scene's time
    unit); ``start``: {slice name: value} of the initial state (or set ``y0`` later)."""

    def __init__(self, name, bodies, motion, interactions, t0=0.0, start=None, meta=None):
        self.name, self.motion, self.t0 = name, motion, float(t0)
        self.bodies = {body.name: body for body in bodies}
        self.interactions = tuple(interactions)
        self.meta = dict(meta or {})
        self._check()
        self.layout = Layout([*motion.slices(), *(part for body in bodies if body.rotator is not None
                                                  for part in body.rotator.slices(body.name))])
        source, code = rhs_source(self)
        self.sources = {"rhs": source}
        lone = self.lone_rigid_body
        if lone is not None:
            self.sources["torque"], torque_code = torque_source(self, lone, code.params)
            self.sources["frame_rate"], frame_code = frame_rate_source(self, lone, code.params)
            code.bindings.update(torque_code.bindings)
        self.parameters = dict(code.params)
        self.params = tuple(as_array(value) for value in self.parameters.values())
        self.rhs = link_source("rhs", source, **_bindings(code, source))
        self.torque = self.frame_rate = None
        if lone is not None:
            self.torque = link_source("torque", self.sources["torque"],
                                      **_bindings(torque_code, self.sources["torque"]))
            self.frame_rate = link_source("frame_rate", self.sources["frame_rate"],
                                          **_bindings(frame_code, self.sources["frame_rate"]))
        self.y0 = None if start is None else self.layout.pack(start)

    def _check(self):
        known = set(self.bodies) | set(self.motion.names)
        for interaction in self.interactions:
            unknown = [b for b in interaction.bodies() if b not in known]
            if unknown:
                raise KeyError(f"{type(interaction).__name__} names {unknown}, which are not bodies of the system: "
                               f"{sorted(known)}")

    @property
    def lone_rigid_body(self):
        """The name of the System's only body when it is a rigid body at the origin without distortion
        (a rigid body under an external torque), else None."""
        turning = [name for name, body in self.bodies.items() if body.rotator is not None]
        if len(turning) != 1 or self.layout.size != 7:
            return None
        rotator = self.bodies[turning[0]].rotator
        if type(rotator) is not Rigid or rotator.distortion is not None:
            return None
        return turning[0]

    @property
    def moments(self):
        """Principal moments of the lone rigid body (what splitting integrators turn), or of the first turning body."""
        name = self.lone_rigid_body or next(n for n, b in self.bodies.items() if b.rotator is not None)
        return self.bodies[name].figure.moments

    def with_start(self, t0, y0):
        """The same System (compiled functions shared) started at (t0, y0), its quaternions made unit."""
        other = copy.copy(self)
        other.t0, other.y0 = float(t0), self.layout.normalise_state(y0)
        return other

    def state(self, y, name):
        """The slice ``name`` of a state (or states (n, size))."""
        return np.asarray(y)[..., self.layout[name]]

    def expressions(self, scales=None):
        """(heyoka variables, their derivatives' expressions) of the state (divided by ``scales``, one per
        component): the generated rhs run on expressions (spinorbit.models.trace), what the Taylor integrator
        compiles; NotTraceable (a ValueError naming the kernel) where the System reads an ephemeris."""
        from .trace import expressions

        return expressions(self, scales)

    @functools.cached_property
    def traceable(self):
        """True when :meth:`expressions` can be built (every term a function of the state and the time)."""
        try:
            self.expressions()
        except ValueError:
            return False
        return True

    @functools.cached_property
    def _invariants(self):
        functions = {}
        for make in (energy_source, angular_momentum_source):
            source, code = make(self)
            functions[code.name] = (link_source(code.name, source, **_bindings(code, source)),
                                    tuple(as_array(v) for v in code.params.values()))
        return functions

    def invariants(self, states, t=None):
        """(energy (n,), angular momentum (n, 3)) of a closed System's states (n, size), G-scaled."""
        states = np.atleast_2d(states)
        t = np.full(len(states), self.t0) if t is None else np.asarray(t, dtype=float)
        (energy, p_e), (momentum, p_l) = self._invariants["energy"], self._invariants["angular_momentum"]
        return (np.array([energy(ti, y, p_e) for ti, y in zip(t, states)]),
                np.array([momentum(ti, y, p_l) for ti, y in zip(t, states)]))

    def figure_axes(self, name, t, states):
        """Figure axes (n, 3, inertial) of body ``name`` at TDB days t: a Gyroscopic body's from its spin to third
        order in the Oppolzer terms (spinorbit.models.start.oppolzer_axes), an attitude's third column otherwise."""
        from ..base.rotations import matrices_from_quats
        from .start import oppolzer_axes

        states = np.atleast_2d(states)
        if isinstance(self.bodies[name].rotator, Gyroscopic):
            return oppolzer_axes(self, name, t, self.state(states, f"{name}.spin"), states)
        return matrices_from_quats(self.state(states, f"{name}.q"))[:, :, 2]

    def __repr__(self):
        return f"System({self.name!r}, {self.layout}, {len(self.interactions)} interactions)"


def _bindings(code, source):
    """The kernels a generated source calls (np is the generated module's own)."""
    return {name: kernel for name, kernel in code.bindings.items() if name in source}
