"""Rotators: how a body of a System turns.  Each names its part of the state and writes its part of the code.

* :class:`Rigid` -- attitude q (body -> inertial) and angular velocity w (body axes), Euler's equations
  (Euler ch. 15 §808-813); with a :class:`Distortion`, the inertia the torques act with is tidally and
  rotationally distorted (spinorbit.models.distortion);
* :class:`MantleCore` -- the same mantle with a fluid core w_c (mantle axes) coupled by friction and by the
  fluid's pressure on an oblate boundary (spinorbit.models.spin, Folkner et al. 2014);
* :class:`Gyroscopic` -- an axisymmetric body that carries only its spin angular momentum l (inertial axes),
  its figure axis from l by the Oppolzer terms (spinorbit.models.gyroscopic);
* :class:`Fixed` -- a figure held in space, with no state (the Sun's in the ephemerides).

The inertia every torque acts with is the body's figure (``Figure.moments``, principal axes, G-scaled), its
anisotropy scaled by (1 + k t) where the figure changes secularly (the Earth's J2 rate), plus the distortion;
Euler's equations turn the undistorted moments.  Each quantity is written into the code once, when first asked.
"""
from dataclasses import dataclass

import numpy as np

from ..base.rotations import cross3, diag3, dot3, matrix_from_quat, matvec3, put, quat_rate
from . import distortion as distortion_kernels
from . import gyroscopic, spin


@dataclass(frozen=True)
class Distortion:
    """The tide raised on the body by ``raiser`` and its spin's flattening (DE421's lunar model):
    ``tide`` = k2 GM_raiser R^5 (km^8/d^2), ``spin`` = k2 R^5 / 3 (km^5), the tide's delay (d), the mean
    motion that the rotational term refers to (rad/d)."""

    raiser: str
    tide: float
    spin: float
    delay_d: float
    mean_motion_rad_d: float

    def apply(self, code, name, rot, omega, inertia):
        """Emit the distorted inertia (into ``inertia``) and return its rate's variable."""
        tau = code.param(f"{name}_tide_delay_d", self.delay_d)
        then, then_v = code.system.motion.delayed(code, name, self.raiser, tau)
        r_del, v_del, delta, rate = (code.local(s) for s in ("r_del", "v_del", "delta", f"inertia_rate_{name}"))
        code.line(f"{r_del}, {v_del} = {code.bind(distortion_kernels.delayed_in_body)}({rot}, {omega}, {then}, "
                  f"{then_v}, {tau})")
        code.line(f"{delta}, {rate} = {code.bind(distortion_kernels.distortion)}({omega}, {r_del}, {v_del}, "
                  f"{code.param(f'{name}_tide_strength', self.tide)}, "
                  f"{code.param(f'{name}_spin_strength', self.spin)}, "
                  f"{code.param(f'{name}_mean_motion', self.mean_motion_rad_d)})")
        code.line(f"{inertia} = {inertia} + {delta}")
        return rate


class Rotator:
    """What every rotator offers the code: moments, inertia (with its rate), attitude matrix, spin."""

    distortion = None

    def moments(self, code, name):
        return code.param(f"{name}_moments", code.system.bodies[name].figure.moments)

    def inertia(self, code, name):
        """(variable: the inertia tensor the torques act with, variable of its rate or None)."""
        def emit():
            figure = code.system.bodies[name].figure
            inertia = code.local(f"inertia_{name}")
            if figure.anisotropy_rate_per_d:
                rate = code.param(f"{name}_anisotropy_rate", figure.anisotropy_rate_per_d)
                code.line(f"{inertia} = {code.bind(diag3)}({self.moments(code, name)}) * (1.0 + {rate} * t)")
            else:
                code.line(f"{inertia} = {code.bind(diag3)}({self.moments(code, name)})")
            if self.distortion is None:
                return inertia, None
            q, omega = self.attitude(code, name)
            return inertia, self.distortion.apply(code, name, self.rot(code, name), omega, inertia)
        return code.once(("inertia", name), emit)


class _Attitude(Rotator):
    """Shared by the rotators that carry an attitude quaternion and the angular velocity in body axes."""

    parts: tuple = ()

    def slices(self, name):
        return [(f"{name}.q", 4, "quaternion", "body -> inertial"), (f"{name}.omega", 3, "vector", "rad/d, body axes"),
                *((f"{name}.{part}", 3, "vector", unit) for part, unit in self.parts)]

    def attitude(self, code, name):
        """Variables (q, w)."""
        def emit():
            q, omega = code.local(f"q_{name}"), code.local(f"omega_{name}")
            code.line(f"{q}, {omega} = y[{_span(code, f'{name}.q')}], y[{_span(code, f'{name}.omega')}]")
            return q, omega
        return code.once(("attitude", name), emit)

    def rot(self, code, name):
        def emit():
            rot = code.local(f"rot_{name}")
            code.line(f"{rot} = {code.bind(matrix_from_quat)}({self.attitude(code, name)[0]})")
            return rot
        return code.once(("rot", name), emit)

    def spin(self, code, name):
        """Variable: the angular velocity in inertial axes."""
        def emit():
            spin_var = code.local(f"spin_{name}")
            code.line(f"{spin_var} = {code.bind(matvec3)}({self.rot(code, name)}, {self.attitude(code, name)[1]})")
            return spin_var
        return code.once(("spin", name), emit)

    def _quaternion_rate(self, code, name, dy):
        q, omega = self.attitude(code, name)
        frame = code.frame_rates.get(name)
        rate = (f"{code.bind(spin.quat_rate_in_frame)}({q}, {omega}, {self.rot(code, name)}, {frame})" if frame
                else f"{code.bind(quat_rate)}({q}, {omega})")
        code.line(f"{code.bind(put)}({dy}[{_span(code, f'{name}.q')}], {rate})")

    def kinetic_energy(self, code, name):
        omega = self.attitude(code, name)[1]
        return f"0.5 * {code.bind(dot3)}({omega}, {self.moments(code, name)} * {omega})"

    def angular_momentum(self, code, name):
        omega = self.attitude(code, name)[1]
        return f"{code.bind(matvec3)}({self.rot(code, name)}, {self.moments(code, name)} * {omega})"


@dataclass(frozen=True)
class Rigid(_Attitude):
    """A rigid body: q (4), w (3)."""

    distortion: Distortion | None = None

    def derivatives(self, code, name, dy):
        self._quaternion_rate(code, name, dy)
        omega = self.attitude(code, name)[1]
        torque = code.torque(name, "body") or "np.zeros(3)"
        if self.distortion is None:
            rate = f"{code.bind(spin.euler_omega_dot)}({self.moments(code, name)}, {omega}, {torque})"
        else:
            inertia, inertia_rate = self.inertia(code, name)
            rate = f"{code.bind(spin.distorted_omega_dot)}({inertia}, {inertia_rate}, {omega}, {torque})"
        code.line(f"{code.bind(put)}({dy}[{_span(code, f'{name}.omega')}], {rate})")


@dataclass(frozen=True)
class MantleCore(_Attitude):
    """A mantle (q, w as :class:`Rigid`) and a fluid core w_c (3, mantle axes): ``core_c`` = C_c and ``friction``
    = k_v in the figure's inertia unit (per day), ``core_flattening`` = (C_c - A_c)/C_c."""

    core_c: float = 0.0
    core_flattening: float = 0.0
    friction: float = 0.0
    distortion: Distortion | None = None
    parts: tuple = (("omega_core", "rad/d, mantle axes"),)

    def derivatives(self, code, name, dy):
        self._quaternion_rate(code, name, dy)
        omega = self.attitude(code, name)[1]
        inertia, inertia_rate = self.inertia(code, name)
        torque = code.torque(name, "body") or "np.zeros(3)"
        core, mantle_rate, core_rate = code.local(f"omega_core_{name}"), code.local("mantle_rate"), code.local(
            "core_rate")
        code.line(f"{core} = y[{_span(code, f'{name}.omega_core')}]")
        code.line(f"{mantle_rate}, {core_rate} = {code.bind(spin.mantle_and_core_rates)}({omega}, {core}, "
                  f"{inertia}, {inertia_rate or 'np.zeros((3, 3))'}, {torque}, "
                  f"{code.param(f'{name}_core_c', self.core_c)}, "
                  f"{code.param(f'{name}_core_flattening', self.core_flattening)}, "
                  f"{code.param(f'{name}_core_friction', self.friction)})")
        code.line(f"{code.bind(put)}({dy}[{_span(code, f'{name}.omega')}], {mantle_rate})")
        code.line(f"{code.bind(put)}({dy}[{_span(code, f'{name}.omega_core')}], {core_rate})")

    def _core(self, code, name):
        """Variables (the core's moments (A_c, A_c, C_c), its angular velocity w_c) of the invariants."""
        def emit():
            moments, omega_core = code.local(f"core_moments_{name}"), code.local(f"omega_core_{name}")
            c_c, f_c = code.param(f"{name}_core_c", self.core_c), code.param(f"{name}_core_flattening",
                                                                              self.core_flattening)
            code.line(f"{moments} = np.array([{c_c} * (1.0 - {f_c}), {c_c} * (1.0 - {f_c}), {c_c}])")
            code.line(f"{omega_core} = y[{_span(code, f'{name}.omega_core')}]")
            return moments, omega_core
        return code.once(("core", name), emit)

    def kinetic_energy(self, code, name):
        """The mantle's (I - I_c) and the core's I_c kinetic energies."""
        omega, (core, omega_core) = self.attitude(code, name)[1], self._core(code, name)
        dot = code.bind(dot3)
        return (f"0.5 * ({dot}({omega}, ({self.moments(code, name)} - {core}) * {omega}) "
                f"+ {dot}({omega_core}, {core} * {omega_core}))")

    def angular_momentum(self, code, name):
        """R ((I - I_c) w + I_c w_c): the mantle's and the core's."""
        omega, (core, omega_core) = self.attitude(code, name)[1], self._core(code, name)
        return (f"{code.bind(matvec3)}({self.rot(code, name)}, ({self.moments(code, name)} - {core}) * {omega} "
                f"+ {core} * {omega_core})")


@dataclass(frozen=True)
class Fixed(Rotator):
    """A figure held in space (no state): ``rot`` its body-to-inertial matrix (3, 3).  The DE ephemerides hold
    the Sun's pole fixed (its J2 acting on the planets); torques on it are dropped."""

    rot_matrix: tuple

    def slices(self, name):
        return []

    def rot(self, code, name):
        return code.param(f"{name}_orientation", np.ascontiguousarray(self.rot_matrix, dtype=float))

    def spin(self, code, name):
        return "np.zeros(3)"

    def derivatives(self, code, name, dy):
        pass

    def kinetic_energy(self, code, name):
        return "0.0"

    def angular_momentum(self, code, name):
        return "np.zeros(3)"


@dataclass(frozen=True)
class Gyroscopic(Rotator):
    """An axisymmetric body carrying its spin angular momentum l (3, inertial, G-scaled: km^5/d^3); the
    torques act on its figure axis, from l by the Oppolzer terms of the point masses acting on its figure."""

    def slices(self, name):
        return [(f"{name}.spin", 3, "vector", "G-scaled angular momentum, inertial")]

    def angular_momentum_variable(self, code, name):
        def emit():
            l_spin = code.local(f"l_{name}")
            code.line(f"{l_spin} = y[{_span(code, f'{name}.spin')}]")
            return l_spin
        return code.once(("l", name), emit)

    def rot(self, code, name):
        def emit():
            l_spin, axis, rot = self.angular_momentum_variable(code, name), code.local(f"axis_{name}"), code.local(
                f"rot_{name}")
            inertia = self.inertia(code, name)[0]
            attractors = oppolzer_attractors(code.system, name)
            if attractors:
                rows, gm = code.rows(name, attractors)
                tensor = code.local(f"tidal_tensor_{name}")
                code.line(f"{tensor} = {code.bind(gyroscopic.tidal_tensor)}({rows}, {gm})")
                code.line(f"{axis} = {code.bind(gyroscopic.figure_axis)}({l_spin}, {tensor}, "
                          f"{self.moments(code, name)}[0], {inertia}[2, 2] - {inertia}[0, 0])")
            else:
                code.line(f"{axis} = {l_spin} / np.sqrt({code.bind(dot3)}({l_spin}, {l_spin}))")
            code.line(f"{rot} = {code.bind(gyroscopic.frame_from_axis)}({axis})")
            return rot
        return code.once(("rot", name), emit)

    def spin(self, code, name):
        """Variable: the angular velocity l / C (inertial axes)."""
        def emit():
            spin_var = code.local(f"spin_{name}")
            code.line(f"{spin_var} = {self.angular_momentum_variable(code, name)} / {self.moments(code, name)}[2]")
            return spin_var
        return code.once(("spin", name), emit)

    def derivatives(self, code, name, dy):
        l_spin = self.angular_momentum_variable(code, name)
        torque = code.torque(name, "inertial") or "np.zeros(3)"
        frame = code.frame_rates.get(name)
        rate = f"{torque} + {code.bind(cross3)}({frame}, {l_spin})" if frame else torque
        code.line(f"{code.bind(put)}({dy}[{_span(code, f'{name}.spin')}], {rate})")

    def kinetic_energy(self, code, name):
        l_spin = self.angular_momentum_variable(code, name)
        return f"0.5 * {code.bind(dot3)}({l_spin}, {l_spin}) / {self.moments(code, name)}[2]"

    def angular_momentum(self, code, name):
        return self.angular_momentum_variable(code, name)


def oppolzer_attractors(system, name):
    """The point masses whose tidal tensor acts on body ``name``'s degree-2 figure (its Oppolzer terms), as the
    interactions on it say (``Interaction.tidal_attractors``)."""
    return tuple(b for i in system.interactions for b in i.tidal_attractors(name))


def _span(code, name):
    index = code.system.layout[name]
    return f"{index.start}:{index.stop}"
