"""The one table of the solar system's attracting bodies: name, NAIF codes, and where the DE421 header keeps its
GM and its initial state (Folkner, Williams & Boggs 2008, IPN PR 42-178).

Every list of bodies derives from :data:`BODIES`: the NAIF codes an SPK kernel is read with
(spinorbit.orbits.kernel), the GMs (:func:`gm_km3_d2`, the one GM table), the bodies an N-body run carries
(:func:`integrated`, spinorbit.orbits.nbody and spinorbit.orbits.solution; the bodies of the solar-system
assemblies) and the header's initial conditions (spinorbit.models.start).  A new attracting
body is one row here.
"""
from dataclasses import dataclass

from ..base.errors import InputError
from .de421_header import header


@dataclass(frozen=True)
class Attractor:
    """One row: ``naif`` the codes to try in a kernel, first found wins (the planet's centre, else its system's
    barycentre); ``gm_key`` the header key of its GM (au^3/d^2; None: the Earth and the Moon share GMB by EMRAT,
    a barycentre has no mass of its own); ``state_key`` the suffix of its initial state in the header (X<k>,
    XD<k>; None: not there); ``integrated``: a body an N-body run carries (and the solar-system assemblies)."""

    name: str
    naif: tuple
    gm_key: str | None = None
    state_key: str | None = None
    integrated: bool = True


# In the order the N-body runs add them (REBOUND's sums follow it).
BODIES = {row.name: row for row in (
    Attractor("sun", (10,), "GMS", "S"),
    Attractor("mercury", (199, 1), "GM1", "1"),
    Attractor("venus", (299, 2), "GM2", "2"),
    Attractor("earth", (399,)),
    Attractor("moon", (301,), state_key="M"),
    Attractor("mars", (499, 4), "GM4", "4"),
    Attractor("jupiter", (5,), "GM5", "5"),
    Attractor("saturn", (6,), "GM6", "6"),
    Attractor("uranus", (7,), "GM7", "7"),
    Attractor("neptune", (8,), "GM8", "8"),
    Attractor("pluto", (9,), "GM9", "9"),
    Attractor("earth_moon_barycenter", (3,), state_key="B", integrated=False),
    Attractor("solar_system_barycenter", (0,), integrated=False),
)}
EMB = "earth_moon_barycenter"


def gm_km3_d2(name):
    """GM of a body from the DE421 header (planets: their systems'), km^3/d^2."""
    h = header()
    if name in ("earth", "moon"):
        earth_share = h["EMRAT"] / (1 + h["EMRAT"])
        gm = h["GMB"] * (earth_share if name == "earth" else 1 - earth_share)
    elif name in BODIES and BODIES[name].gm_key:
        gm = h[BODIES[name].gm_key]
    else:
        raise InputError("body", name, f"a body with a GM: {sorted(n for n in BODIES if has_gm(n))}")
    return gm * h["AU"] ** 3


def has_gm(name):
    return name in ("earth", "moon") or (name in BODIES and BODIES[name].gm_key is not None)


def integrated():
    """The bodies an N-body run carries, in order."""
    return tuple(name for name, row in BODIES.items() if row.integrated)


def heliocentric_set():
    """The N-body bodies with the Earth and the Moon as their barycentre, in order: the solar system seen from
    the Sun's side (the deep-time solution, the Earth-Moon pair's external bodies)."""
    return tuple(EMB if name == "earth" else name for name in integrated() if name != "moon")
