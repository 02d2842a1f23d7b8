"""The Moon's physical libration on an ephemeris: four levels, each adding physics to the one before.

1. Euler's model: a rigid degree-2 Moon, the Earth and the Sun as point masses (Euler ch. 16 P91, §815);
2. + the Moon's degree-3 and degree-4 field acting with every point mass (Williams, Boggs & Folkner 2008);
3. + an oblate fluid core, the tidal and rotational distortion of the mantle's inertia and the Earth's J2
   acting on the Moon's degree-2 figure (Folkner et al. 2014, IPN PR 42-196, §III; the equations in
   spinorbit.models.spin and spinorbit.models.distortion);
4. + Venus, Mars, Jupiter and Saturn on the figure.

The Moon sits at the origin and the attracting bodies come from the orbit source relative to it (Centred); the
Moon is DE421's (spinorbit.models.assemblies.earth_moon.moon_body).  What limited the pole, measured against
DE421 over 1900-2050: DE421's core is oblate (header COBLAT, f_c = 3.8e-4); its pressure torque couples the
core's free precession (~200 yr) to the mantle; with a spherical core the pole is off by 1.24", with the oblate
core and the Earth's J2 (0.16" alone) by 0.0036", longitude 0.0005".  The published forms matter: the
uncorrected zz element of the rotational distortion (w^2 - n^2) or leaving out dI/dt w moves the pole by 3.3".
"""
from dataclasses import dataclass

import numpy as np

from ...base.errors import InputError
from ...bodies import sun
from ...bodies.de421_header import header
from ..interactions import FigureFigure, Harmonics, PointMass, PoleTable
from ..motion import Centred
from ..system import System
from .earth_moon import moon_body


@dataclass(frozen=True)
class Level:
    """A level of the lunar model: its terms (TERMS), the Moon's own physics, the attracting bodies."""

    name: str
    terms: tuple
    core: bool = False
    tides: bool = False
    bodies: tuple = ("earth", "sun")


LEVELS = {1: Level("Euler: degree-2 Moon, Earth + Sun point masses", ("point_mass",)),
          2: Level("+ Moon degree 3 and 4", ("point_mass", "harmonics")),
          3: Level("+ oblate fluid core, tidal and rotational distortion, Earth's J2 on the figure",
                   ("point_mass", "harmonics", "earth_j2"), core=True, tides=True),
          4: Level("+ Venus, Mars, Jupiter, Saturn on the figure", ("point_mass", "harmonics", "earth_j2"), core=True,
                   tides=True, bodies=("earth", "sun", "venus", "jupiter", "mars", "saturn"))}
TERMS = {"point_mass": "every attracting body as a point mass on the degree-2 figure (Euler P91, §815)",
         "harmonics": "every attracting body on the degree 3-4 field",
         "earth_j2": "the Earth's J2 on the degree-2 figure (its pole: the IAU 1976 mean pole, as DE421)",
         "sun_j2": "the Sun's J2 on the degree-2 figure (its pole: IAU WGCCRE)"}
SUN_POLE = PoleTable(np.array([0.0, 1.0]), np.array([sun.POLE_ICRF, sun.POLE_ICRF]), 0.0)


def term(name, orbits, earth_pole):
    """The interaction ``name`` (TERMS) on the Moon from the bodies of ``orbits`` (relative to the Moon)."""
    bodies = tuple(orbits.names)
    gm = dict(zip(bodies, np.asarray(orbits.gm, dtype=float)))
    if name in ("earth_j2", "sun_j2") and name.split("_")[0] not in bodies:
        raise InputError("terms", name, f"terms whose body is among the orbit's {list(bodies)}")
    if name == "point_mass":
        return PointMass("moon", bodies)
    if name == "harmonics":
        return Harmonics("moon", bodies)
    if name == "earth_j2":
        h = header()
        grid, samples = earth_pole
        return FigureFigure("moon", "earth", PoleTable(grid, samples, gm["earth"] * h["J2E"] * h["RE"] ** 2))
    if name == "sun_j2":
        return FigureFigure("moon", "sun", PoleTable(SUN_POLE.grid, SUN_POLE.samples,
                                                     gm["sun"] * sun.J2 * sun.RADIUS_KM ** 2))
    raise InputError("terms", name, f"one of {sorted(TERMS)}")


def moon(level, orbits, extra_terms=(), tides=True, earth_pole=None, t0=0.0, start=None):
    """The lunar model at ``level`` (LEVELS) with ``extra_terms`` (TERMS), driven by ``orbits`` (the attracting
    bodies relative to the Moon, the Earth first); ``earth_pole``: (grid, samples) of the Earth's pole for
    the earth_j2 term."""
    spec = LEVELS[level]
    gm_earth = float(np.asarray(orbits.gm)[list(orbits.names).index("earth")])
    body = moon_body(distortion=spec.tides and tides, core=spec.core, earth_gm=gm_earth)
    interactions = [term(name, orbits, earth_pole) for name in spec.terms + tuple(extra_terms)]
    return System(f"moon level {level}", [body], Centred("moon", orbits), interactions, t0, start,
                  {"terms": spec.terms + tuple(extra_terms), "tides": spec.tides and tides, "level": level})
