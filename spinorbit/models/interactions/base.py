"""What an interaction is to a System: the bodies it joins, and the code it writes into the right-hand side.

An interaction acts between bodies of a System: it adds forces on their centres (G-scaled, inertial axes;
:meth:`~spinorbit.models.generate.Code.add_force`), torques on their figures (``add_torque``), or rates of the
frames their spin equations hold in (``add_frame_rate``, saying which in ``frames()``), each with its reaction
where one exists (action equals reaction: a figure's torque is minus the moment of its pull on the attracting
masses, Euler §818).  What a rotator needs from the interactions on its body they tell it: a gyroscopic body's
figure axis the point masses whose tidal tensor acts on its degree-2 figure (``tidal_attractors``).
``phase = "orbit"`` interactions (point-mass forces) are written before the rotators' geometry, which may
read the orbit's acceleration so far (the delayed tide); the others after.  ``energy(code)`` is its part of
a closed System's energy, where it has one.
"""

from ...base.errors import PhysicsError


class Interaction:
    """Base of every interaction; subclasses are frozen dataclasses naming their bodies."""

    phase = "figure"
    citation = ""
    reads_places = True         # its code reads where the bodies are (the motion's prologue)

    def bodies(self):
        """The names of the bodies it joins."""
        raise NotImplementedError

    def frames(self):
        """The bodies whose spin frames it turns (``code.add_frame_rate``), e.g. by the geodesic precession."""
        return ()

    def tidal_attractors(self, name):
        """The point masses whose tidal tensor on body ``name``'s degree-2 figure gives this interaction's torque on
        it: what a gyroscopic body's figure axis is found from (its Oppolzer terms, spinorbit.models.gyroscopic).
        An interaction that joins ``name`` says so itself (() when the figure axis leaves its torque out); one
        that does not join it gives none."""
        if name in self.bodies():
            raise PhysicsError(f"{type(self).__name__} acts on {name!r} but does not say which point masses' tidal "
                               f"tensor its torque comes from (tidal_attractors), which a gyroscopic {name!r} needs "
                               "for its figure axis")
        return ()

    def emit(self, code):
        raise NotImplementedError

    def energy(self, code):
        raise PhysicsError(f"{type(self).__name__} has no interaction energy: a System with it is not closed "
                           "(conservation cannot be checked)")


def needs_forces(code, figure, attractors):
    """True when a force on ``figure``'s centre or on any of ``attractors`` changes the state."""
    return code.moves(figure) or any(code.moves(b) for b in attractors)

