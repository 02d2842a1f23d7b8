"""Idealised bodies: Euler's free body (ch. 15 §808) and a rigid body under point masses (ch. 16 P91, §815).

The body sits at the origin with its principal moments in any unit (only their ratios enter); the point masses
move on an orbit source relative to it (analytic circles and ellipses for Euler's problems, an ephemeris for
the stress cases).  These are the Systems of the free-body, P92-P96 and stress scenes.
"""

from ..figure import Body, Figure
from ..interactions import PointMass
from ..motion import Centred
from ..rotators import Rigid
from ..system import System


def free_body(moments, q0, omega0, t0=0.0, name="free body"):
    """A torque-free rigid body (Euler ch. 15 §808) of principal ``moments`` from attitude q0, rate omega0."""
    return System(name, [Body("body", figure=Figure(moments), rotator=Rigid())], Centred("body"), [], t0,
                  {"body.q": q0, "body.omega": omega0})


def under_point_masses(moments, orbit, q0, omega0, t0=0.0, name="rigid body under point masses", rotator=None,
                       omega_core0=None):
    """A body of principal ``moments`` under the P91 torque (§815) of ``orbit``'s point masses: rigid, or turning
    as ``rotator`` says (a MantleCore, its core started at ``omega_core0``, mantle axes)."""
    body = Body("body", figure=Figure(moments), rotator=Rigid() if rotator is None else rotator)
    start = {"body.q": q0, "body.omega": omega0}
    if omega_core0 is not None:
        start["body.omega_core"] = omega_core0
    return System(name, [body], Centred("body", orbit), [PointMass("body", tuple(orbit.names))], t0, start)
