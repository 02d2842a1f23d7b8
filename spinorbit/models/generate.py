"""Writing a System's compiled functions: the right-hand side, the torque on a lone rigid body, the invariants.

A generated function is straight-line code: the motion places the bodies, the interactions add forces,
torques and frame rates to per-body accumulators, the rotators turn them into rates.  Every piece of physics
is a compiled kernel of the package (``spinorbit.models``) that the generated code calls by name; the System's
parameters arrive as one tuple ``p`` whose fields the function unpacks by name.  ``Code`` is the sheet the
pieces write on; :func:`source` is what comes of it.
"""
import numpy as np

from ..base.linker import python_function
from ..base.rotations import mat_t_vec3, matvec3


class Code:
    """The lines of one generated function, its named parameters and the kernels it calls."""

    def __init__(self, system, name, params=None):
        self.system, self.name = system, name
        self.lines, self.params, self.bindings = [], ({} if params is None else params), {}
        self._locals, self._cache = {name, "t", "y", "p", "np"}, {}
        self.torques = {}               # body -> {"body": var, "inertial": var} accumulators
        self.frame_rates = {}           # body -> var (inertial, rad/d)

    # -- what the function reads and calls -------------------------------------------------------
    def param(self, name, value):
        """The parameter ``name`` (a field of the System's parameter record): its local name."""
        if name in self.params and not _same(self.params[name], value):
            raise ValueError(f"parameter {name!r} given twice, with different values")
        self.params[name] = value
        return name

    def bind(self, kernel, name=None):
        """A compiled kernel the function calls: its local name."""
        function = python_function(kernel)
        for candidate in ([name] if name else [function.__name__,
                                               f"{function.__module__.rsplit('.', 1)[-1]}_{function.__name__}"]):
            if candidate not in self._locals and self.bindings.setdefault(candidate, kernel) is kernel:
                return candidate
        raise ValueError(f"two kernels named {candidate!r}")

    def local(self, stem):
        """A fresh local variable name."""
        name, k = stem, 1
        while name in self._locals or name in self.params or name in self.bindings:
            k += 1
            name = f"{stem}_{k}"
        self._locals.add(name)
        return name

    def line(self, text):
        self.lines.append(text)

    def once(self, key, make):
        """The value ``make()`` returned the first time ``key`` was asked for (a variable computed once)."""
        if key not in self._cache:
            self._cache[key] = make()
        return self._cache[key]

    # -- geometry: answered by the motion and the rotators -------------------------------------------
    def relative(self, a, b):
        """Variable: body b seen from body a (km, inertial axes)."""
        return self.once(("rel", a, b), lambda: self.system.motion.relative(self, a, b))

    def relative_velocity(self, a, b):
        """Variable: the velocity of b relative to a (km/d, inertial axes)."""
        return self.once(("relv", a, b), lambda: self.system.motion.relative_velocity(self, a, b))

    def rows(self, a, others):
        """(variable (n, 3): the bodies ``others`` seen from a, variable (n,): their GM)."""
        others = tuple(others)
        return self.once(("rows", a, others), lambda: self.system.motion.rows(self, a, others))

    def moves(self, body):
        """True when a force on ``body`` changes the state (its centre is integrated)."""
        return self.system.motion.moves(body)

    def rotator(self, body):
        rotator = self.system.bodies[body].rotator
        if rotator is None:
            raise ValueError(f"{body!r} has no rotator: no attitude, torque or inertia to act on")
        return rotator

    def rot(self, body):
        """Variable: the body-to-inertial matrix of ``body``."""
        return self.rotator(body).rot(self, body)

    def inertia(self, body):
        """Variable: the inertia tensor (body axes, G-scaled) that the torques act with."""
        return self.rotator(body).inertia(self, body)[0]

    def spin(self, body):
        """Variable: the body's angular velocity in inertial axes (rad/d)."""
        return self.rotator(body).spin(self, body)

    # -- what acts -------------------------------------------------------------------------------
    def add_force(self, body, force):
        """A force (G-scaled, inertial axes) on the centre of ``body``; ignored if its centre is not integrated."""
        if self.moves(body):
            self.system.motion.add_force(self, body, force)

    def add_torque(self, body, torque, axes="body"):
        """A torque on ``body`` (G-scaled), in its body axes or in inertial ones."""
        accumulators = self.torques.setdefault(body, {})
        if axes not in accumulators:
            accumulators[axes] = self.local(f"torque_{body}_{axes}")
            self.line(f"{accumulators[axes]} = np.zeros(3)")
        self.line(f"{accumulators[axes]} += {torque}")

    def add_frame_rate(self, body, rate):
        """A rate (inertial axes, rad/d) of the frame in which ``body``'s equations hold."""
        if body not in self.frame_rates:
            self.frame_rates[body] = self.local(f"frame_rate_{body}")
            self.line(f"{self.frame_rates[body]} = np.zeros(3)")
        self.line(f"{self.frame_rates[body]} += {rate}")

    def torque(self, body, axes):
        """Variable: the total torque on ``body`` in ``axes`` ("body" or "inertial"), or None if none acts."""
        accumulators = self.torques.get(body, {})
        if not accumulators:
            return None
        other = "inertial" if axes == "body" else "body"
        if other not in accumulators:
            return accumulators[axes]
        rot, total = self.rot(body), self.local(f"torque_{body}")
        turn = self.bind(mat_t_vec3 if axes == "body" else matvec3)
        mine = accumulators.get(axes)
        self.line(f"{total} = {turn}({rot}, {accumulators[other]})" + (f" + {mine}" if mine else ""))
        return total

    # -- the text ----------------------------------------------------------------------------------
    def text(self, signature, result):
        """The function's source: unpacks ``p`` into the parameter names, then the lines, then ``return``."""
        names = list(self.params)
        head = [f"def {self.name}({signature}):"]
        if names:
            head.append(f"    ({', '.join(names)}{',' if len(names) == 1 else ''}) = p")
        return "\n".join(head + [f"    {line}" for line in self.lines] + [f"    return {result}"]) + "\n"


def rhs_source(system):
    """(source, Code) of dy/dt = rhs(t, y, p)."""
    code = Code(system, "rhs")
    system.motion.prologue(code)
    for interaction in system.interactions:
        if interaction.phase == "orbit":
            interaction.emit(code)
    for name, body in system.bodies.items():          # a distortion reads the point masses' acceleration so far
        if body.rotator is not None and body.rotator.distortion is not None:
            body.rotator.inertia(code, name)
    for interaction in system.interactions:
        if interaction.phase != "orbit":
            interaction.emit(code)
    dy = code.local("dy")
    code.line(f"{dy} = np.empty({system.layout.size})")
    system.motion.derivatives(code, dy)
    for name, body in system.bodies.items():
        if body.rotator is not None:
            body.rotator.derivatives(code, name, dy)
    return code.text("t, y, p", dy), code


def torque_source(system, name, params):
    """(source, Code) of torque(t, y, p): the body-axes torque on the lone rigid body ``name`` (what splitting
    integrators kick with), reading the rhs's parameter record ``params`` (it adds none)."""
    known = list(params)
    code = Code(system, "torque", params)
    system.motion.prologue(code)
    for interaction in system.interactions:
        interaction.emit(code)
    total = code.torque(name, "body")
    if list(params) != known:
        raise AssertionError(f"the torque added parameters the rhs lacks: {sorted(set(params) - set(known))}")
    return code.text("t, y, p", total or "np.zeros(3)"), code


def frame_rate_source(system, name, params):
    """(source, Code) of frame_rate(t, y, p): the rate (inertial axes, rad/d) of the frame in which the lone rigid
    body ``name``'s equations hold (its geodesic precession), what a splitting integrator turns its attitude by,
    written by the interactions that turn that frame; zeros where none does.  It reads the rhs's parameter record
    ``params`` (it adds none)."""
    known = list(params)
    code = Code(system, "frame_rate", params)
    turning = [interaction for interaction in system.interactions if name in interaction.frames()]
    if any(interaction.reads_places for interaction in turning):
        system.motion.prologue(code)
    for interaction in turning:
        interaction.emit(code)
    if list(params) != known:
        raise AssertionError(f"the frame rate added parameters the rhs lacks: {sorted(set(params) - set(known))}")
    return code.text("t, y, p", code.frame_rates.get(name, "np.zeros(3)")), code


def energy_source(system):
    """(source, Code) of energy(t, y, p): the closed System's total energy (G-scaled, km^5/d^4)."""
    code = Code(system, "energy")
    system.motion.prologue(code)
    total = code.local("total")
    code.line(f"{total} = {system.motion.kinetic_energy(code)}")
    for name, body in system.bodies.items():
        if body.rotator is not None:
            code.line(f"{total} += {body.rotator.kinetic_energy(code, name)}")
    for interaction in system.interactions:
        code.line(f"{total} += {interaction.energy(code)}")
    return code.text("t, y, p", total), code


def angular_momentum_source(system):
    """(source, Code) of angular_momentum(t, y, p): the closed System's total angular momentum (inertial)."""
    code = Code(system, "angular_momentum")
    system.motion.prologue(code)
    total = code.local("total")
    code.line(f"{total} = {system.motion.angular_momentum(code)}")
    for name, body in system.bodies.items():
        if body.rotator is not None:
            code.line(f"{total} += {body.rotator.angular_momentum(code, name)}")
    return code.text("t, y, p", total), code


def _same(a, b):
    if a is b:
        return True
    if isinstance(a, (tuple, list)) or isinstance(b, (tuple, list)):
        return False
    return np.array_equal(np.asarray(a), np.asarray(b))


def as_array(value):
    """A parameter as the generated code reads it: float arrays contiguous, tuples element by element."""
    if isinstance(value, tuple):
        return tuple(as_array(v) for v in value)
    if isinstance(value, np.ndarray):
        return np.ascontiguousarray(value, dtype=value.dtype if value.dtype.kind == "i" else float)
    return value
