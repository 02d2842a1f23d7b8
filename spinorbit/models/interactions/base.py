"""What an interaction is to a System: the bodies it joins, and the code it writes into the right-hand side.

An interaction acts between bodies of a System: it adds forces on their centres (G-scaled, inertial axes;
:meth:`~spinorbit.models.generate.Code.add_force`), torques on their figures (``add_torque``), or rates of the
frames their spin equations hold in (``add_frame_rate``), each with its reaction where one exists (action
equals reaction: a figure's torque is minus the moment of its pull on the attracting masses, Euler §818).
``phase = "orbit"`` interactions (point-mass forces) are written before the rotators' geometry, which may
read the orbit's acceleration so far (the delayed tide); the others after.  ``energy(code)`` is its part of
a closed System's energy, where it has one.
"""

from ...errors import PhysicsError


class Interaction:
    """Base of every interaction; subclasses are frozen dataclasses naming their bodies."""

    phase = "figure"
    citation = ""

    def bodies(self):
        """The names of the bodies it joins."""
        raise NotImplementedError

    def emit(self, code):
        raise NotImplementedError

    def energy(self, code):
        raise PhysicsError(f"{type(self).__name__} has no interaction energy: a System with it is not closed "
                           "(conservation cannot be checked)")


def needs_forces(code, figure, attractors):
    """True when a force on ``figure``'s centre or on any of ``attractors`` changes the state."""
    return code.moves(figure) or any(code.moves(b) for b in attractors)

