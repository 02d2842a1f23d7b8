"""The solar system integrated as one: the Sun, Mercury to Neptune, Pluto, the Earth and the Moon, every centre in
the state (spinorbit.models.barycentric), with DE421's model of them (Folkner et al. 2014, IPN PR 42-196, §III;
constants from the DE421 header, spinorbit.bodies.de421_header).

Bodies: the Sun (GMS; J2SUN at ASUN about the IAU pole, held fixed as the ephemerides hold it), the planets'
systems as point masses (GM1 ... GM9, Mars to Pluto with their moons, as DE421 integrates them), the Earth and
the Moon as in the Earth-Moon assembly (spinorbit.models.assemblies.earth_moon: the gyroscopic Earth with J2E,
J3E, J4; the Moon's mantle, fluid core, degree 2-4 field, tidal and rotational distortion).  Interactions, each
with its reaction: Newton and EIH between every pair; the Sun's J2 with every other body; the Earth's and the
Moon's figures with each other, with the Sun and (a switch) the planets with the Moon's; the Earth's tides; the
geodesic precession of the Earth's spin.  Not here: DE421's 343 asteroids (their share of what is left is
estimated in the solar-system scene).

:func:`solar_system` builds DE421's model; :func:`closed` the same bodies with what conserves energy and angular
momentum only (Newton, the figures; the Sun turning gyroscopically so that its J2's torque has a reaction).
"""
import math

import numpy as np

from ...bodies import sun
from ...bodies.de421_header import header
from ...bodies.table import gm_km3_d2, integrated
from ..barycentric import Barycentric
from ..figure import Body, Figure
from ..interactions import Newton, PointMass, Relativity
from ..rotators import Fixed, Gyroscopic
from ..start import frame
from ..system import System
from . import earth_moon

FREE = tuple(name for name in integrated() if name not in ("earth", "moon"))
PLANETS = FREE[1:]
SWITCHES = {**{name: text for name, text in earth_moon.SWITCHES.items() if name != "planets"},
            "sun_j2": "the Sun's J2 (DE421's J2SUN, the IAU pole) on every other body"}
SUN_SPIN_RAD_D = 2 * math.pi / sun.SIDEREAL_ROTATION_D


def sun_body(turning=False):
    """The Sun of DE421: GMS, J2SUN at ASUN about the IAU pole, held fixed (or ``turning``: gyroscopic, with
    C/(M R^2) = 0.070)."""
    gm, h = gm_km3_d2("sun"), header()
    c_minus_a = h["J2SUN"] * gm * h["ASUN"] ** 2
    c = sun.C_MR2 * gm * h["ASUN"] ** 2
    rotator = Gyroscopic() if turning else Fixed(frame(sun.POLE_ICRF, np.array([1.0, 0.0, 0.0])))
    return Body("sun", gm, Figure(np.array([c - c_minus_a, c - c_minus_a, c])), rotator)


def bodies(switches=tuple(SWITCHES), turning_sun=False, extra=()):
    """[the Sun, the planets, the ``extra`` point masses ((name, GM km^3/d^2), ...), the Moon, the Earth] and the
    motion that carries them."""
    moon, earth = earth_moon.moon_body("moon_distortion" in switches), earth_moon.earth_body()
    points = [Body(name, gm_km3_d2(name)) for name in PLANETS] + [Body(name, gm) for name, gm in extra]
    free = (*FREE, *(name for name, _ in extra))
    motion = Barycentric(free, tuple(b.gm for b in [sun_body(), *points]), "earth", "moon", earth.gm, moon.gm)
    return [sun_body(turning_sun), *points, moon, earth], motion


def solar_system(switches=tuple(SWITCHES), t0=0.0, start=None, extra=()):
    """DE421's solar system (module docstring) with the ``switches`` (SWITCHES) on, and ``extra`` point masses
    ((name, GM km^3/d^2), ...: an asteroid, to see what it moves): a System."""
    unknown = sorted(set(switches) - set(SWITCHES))
    if unknown:
        from ...base.errors import InputError

        raise InputError("switches", unknown, f"names from {list(SWITCHES)}")
    members, motion = bodies(switches, extra=extra)
    orbit = [Newton()] + ([Relativity(earth_moon.c_km_d())] if "relativity" in switches else [])
    sun_j2 = [PointMass("sun", (*PLANETS, "earth", "moon"))] if "sun_j2" in switches else []
    return System("solar system", members, motion,
                  orbit + sun_j2 + earth_moon.couplings() + earth_moon.solar(_theirs(switches), PLANETS), t0, start,
                  {"switches": tuple(switches)})


def _theirs(switches):
    """The switches the Earth-Moon assembly knows."""
    return tuple(name for name in switches if name in earth_moon.SWITCHES)


def closed(t0=0.0, start=None):
    """The solar system with no dissipation and no frame rate: Newton, the Sun's J2 (the Sun turning), the Earth's
    and the rigid Moon's figures with each other, the Sun and the planets; what conserves its momentum, angular
    momentum and energy."""
    members, motion = bodies((), turning_sun=True)
    members = [*members[:-2], earth_moon.moon_body(distortion=False, core=False), members[-1]]
    figures = [PointMass("sun", (*PLANETS, "earth", "moon")), *earth_moon.couplings(),
               *earth_moon.solar(("planets_on_moon_figure", "sun_on_earth_j3_j4"), PLANETS)]
    return System("solar system (closed)", members, motion, [Newton(), *figures], t0, start)
