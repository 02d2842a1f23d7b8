"""Satellites as rings held to a planet's equator: their share of the point masses' torque on the planet.

A close satellite's orbit precesses about the planet's equator (its Laplace plane) in days to years, so fast
against the planet's own precession that, averaged, the orbit is a ring of the satellite's mass m at its
semi-major axis a turning with the equator (Goldreich 1965, AJ 70, 5; Kinoshita 1993, Celest. Mech. 57, 359
for Phobos and Deimos).  The Sun's torque on the ring reaches the planet through the satellite's pull on the
equatorial bulge: the ring adds to the figure the torques act on the inertia diag(m a^2/2, m a^2/2, m a^2),
and the torque is Euler's P91 (§815) on that inertia (point_mass.torque).  Its own angular momentum
(m sqrt(GM a), 1e-6 of Mars's spin for Phobos) is left out, and so is its share of a gyroscopic figure
axis's Oppolzer terms (the ring's inertia over the body's, 3e-5 of a 1e-9 rad offset for Mars).
"""
from dataclasses import dataclass

import numpy as np

from .base import Interaction
from .point_mass import torque


def ring_inertia(satellites):
    """The rings' inertia (3, 3), G-scaled (km^5/d^2), of ``satellites`` = ((name, GM km^3/d^2, a km), ...)."""
    total = sum(gm * a * a for _, gm, a in satellites)
    return np.diag([0.5 * total, 0.5 * total, total])


@dataclass(frozen=True)
class Rings(Interaction):
    """``attractors`` as point masses on the rings of inertia ``inertia`` (3, 3, body axes) held to
    ``figure``'s equator."""

    figure: str
    attractors: tuple
    inertia: np.ndarray
    citation = "Euler, Theoria motus ch. 16 P91 (§815); Goldreich 1965"

    def bodies(self):
        return (self.figure, *self.attractors)

    def tidal_attractors(self, name):
        """None: the figure axis keeps the body's own Oppolzer terms (module docstring)."""
        return ()

    def emit(self, code):
        rows, gm = code.rows(self.figure, self.attractors)
        ring = code.param(f"{self.figure}_ring_inertia", np.asarray(self.inertia, dtype=float))
        code.add_torque(self.figure, f"{code.bind(torque, 'point_mass_torque')}({code.rot(self.figure)}, {ring}, "
                                     f"{rows}, {gm})")
