"""The Earth-Moon system integrated as one: the Moon's orbit, the Moon's mantle and core and the Earth's spin
in one state, coupled both ways; the Sun, the planets and the Earth-Moon barycentre from an orbit source.

State: ``moon.r``, ``moon.v`` (the Moon from the Earth, km, km/d, ICRF); ``moon.q``, ``moon.omega``,
``moon.omega_core`` (the lunar model of DE421: moments, field to degree 4, oblate fluid core, tidal and rotational
distortion; spinorbit.models.rotators.MantleCore); ``earth.spin`` (the Earth's spin angular momentum, G-scaled,
ICRF: a gyroscopic Earth, its figure axis from it by the Oppolzer terms).  The Earth is axisymmetric with
C - A = J2E M RE^2 (the DE421 header's J2, as DE421 lets it act on the orbit) and C = (C - A)/H_d (IAU 2006's
dynamical ellipticity, which sets the precession rate; C/(M RE^2) = 0.330694), J3 from the header (J3E) and
J4 from EGM2008 (bodies.earth.J4): the header's J4E is +1.619974e-6, the opposite of the Earth's known sign.

Interactions (each with its reaction; Euler §818; Folkner et al. 2014, IPN PR 42-196): Newton (the pair's
monopole and the Sun's and planets' pulls), EIH; the Moon's degree 2-4 and the Earth's degree 2 with the Earth,
the Moon and the Sun as point masses, the Earth's J3-J4 with the Moon, the Earth's J2 on the Moon's degree 2;
the Earth's tides raised by the Moon and the Sun; the geodesic precession of the Earth's spin.  The planets'
torques on the Moon's figure (level 4) and the Sun's on the Earth's J3 and J4 are switches like the others.

:func:`solar_system` builds it on an orbit source; :func:`closed` is the same assembly with the orbit source
removed (no Sun, planets or barycentre: the pair about its barycentre at rest), the switches choosing what acts.
"""
import math

import numpy as np

from ...base.constants import DAY_S
from ...base.errors import InputError
from ...bodies import earth
from ...bodies.de421_header import header
from ...bodies.moon import de421
from ...bodies.table import gm_km3_d2, heliocentric_set
from ..figure import Body, Field, Figure
from ..interactions import FigureFigure, Geodesic, Harmonics, Newton, PointMass, Relativity, Tides
from ..motion import Pair
from ..rotators import Distortion, Gyroscopic, MantleCore, Rigid
from ..system import System

EXTERNAL = heliocentric_set()
PLANETS = tuple(name for name in EXTERNAL if name not in ("sun", "earth_moon_barycenter"))
SWITCHES = {"relativity": "the EIH (1PN) point-mass correction on the orbit",
            "earth_tides": "the tides raised on the Earth by the Moon and the Sun (DE421's K2E, TAUE)",
            "moon_distortion": "the Moon's tidal and rotational distortion (DE421's K2M, TAUM)",
            "geodesic": "the geodesic precession of the Earth's axis",
            "planets": "Mercury to Pluto as point masses on the orbit",
            "planets_on_moon_figure": "the planets' torques on the Moon's degree-2 figure",
            "sun_on_earth_j3_j4": "the Sun's torque on the Earth's J3 and J4"}
FIGURES = {"moon_figure": "the Moon's degree 2 and the Earth as a point mass",
           "moon_harmonics": "the Moon's degrees 3-4 (DE421) and the Earth as a point mass",
           "earth_figure": "the Earth's degree 2 (J2E, H_d) and the Moon as a point mass",
           "earth_harmonics": "the Earth's J3 (DE421 header), J4 (EGM2008) and the Moon as a point mass",
           "figure_figure": "the Earth's J2 with the Moon's degree 2"}
MOON_MEAN_MOTION_RAD_D = 2 * math.pi / 27.321661          # sidereal month: the rotational distortion's reference


def c_km_d():
    """The speed of light in km/day (DE421's CLIGHT)."""
    return header()["CLIGHT"] * DAY_S


def moon_body(distortion=True, core=True, earth_gm=None):
    """The Moon of DE421 (G-scaled): degree-2 moments, field to degree 4, mantle and oblate fluid core, the tide
    the Earth (GM ``earth_gm``, default DE421's) raises and the spin's flattening."""
    moon = de421()
    earth_gm = gm_km3_d2("earth") if earth_gm is None else earth_gm
    scale = moon.gm_km3_d2 * moon.radius_km ** 2                      # M R^2 -> G I
    c = moon.moments[2] * scale
    field = Field(moon.radius_km, np.ascontiguousarray(moon.c_nm), np.ascontiguousarray(moon.s_nm))
    bulge = Distortion("earth", moon.k2 * earth_gm * moon.radius_km ** 5, moon.k2 * moon.radius_km ** 5 / 3,
                       moon.tau_d, MOON_MEAN_MOTION_RAD_D) if distortion else None
    rotator = (MantleCore(core_c=moon.core_c_over_c * c, core_flattening=moon.core_flattening,
                          friction=moon.kv_over_c_per_d * c, distortion=bulge) if core else Rigid(distortion=bulge))
    return Body("moon", moon.gm_km3_d2, Figure(moon.moments * scale, field), rotator)


def earth_body(rotator=None):
    """The Earth as DE421 lets it act (J2E, J3E at RE; J4 EGM2008), C from IAU 2006's H_d; gyroscopic by default."""
    h, gm = header(), gm_km3_d2("earth")
    c_minus_a = h["J2E"] * gm * h["RE"] ** 2
    c = c_minus_a / earth.H_D
    c_nm = np.zeros((5, 5))
    c_nm[3, 0], c_nm[4, 0] = -h["J3E"], -earth.J4
    figure = Figure(np.array([c - c_minus_a, c - c_minus_a, c]), Field(h["RE"], c_nm, np.zeros((5, 5))))
    return Body("earth", gm, figure, Gyroscopic() if rotator is None else rotator)


def couplings(figures=tuple(FIGURES)):
    """The Earth's and the Moon's figures acting on each other, those named in ``figures`` (FIGURES)."""
    unknown = sorted(set(figures) - set(FIGURES))
    if unknown:
        raise InputError("figures", unknown, f"names from {list(FIGURES)}")
    terms = {"moon_figure": PointMass("moon", ("earth",)), "moon_harmonics": Harmonics("moon", ("earth",)),
             "earth_figure": PointMass("earth", ("moon",)), "earth_harmonics": Harmonics("earth", ("moon",)),
             "figure_figure": FigureFigure("moon", "earth")}
    return [terms[name] for name in figures]


def solar(switches, planets):
    """What the Sun and the planets add, as the ``switches`` (SWITCHES) say: on the orbit (Newton's pulls come
    with :class:`Newton`), on both figures, the tides, the geodesic precession."""
    unknown = sorted(set(switches) - set(SWITCHES))
    if unknown:
        raise InputError("switches", unknown, f"names from {list(SWITCHES)}")
    out = [PointMass("moon", ("sun",)), Harmonics("moon", ("sun",)), PointMass("earth", ("sun",))]
    if "planets_on_moon_figure" in switches and planets:      # their pull on degrees 3-4: < 1e-10 of the Earth's
        out.append(PointMass("moon", planets))
    if "sun_on_earth_j3_j4" in switches:
        out.append(Harmonics("earth", ("sun",)))
    if "earth_tides" in switches:
        love = earth.de421_tides()
        out.append(Tides("earth", "moon", "sun", tuple(love[m] for m in range(3)), header()["RE"]))
    if "geodesic" in switches:
        out.append(Geodesic("earth", "sun", c_km_d()))
    return out


def solar_system(external, switches=tuple(SWITCHES), t0=0.0, start=None):
    """The Earth-Moon system on ``external`` (a HermiteOrbits of EXTERNAL's barycentric states, or of the bodies
    the switches need): a System (module docstring)."""
    carried = [p for p, gm in zip(external.names, external.gm) if p in PLANETS and gm > 0]
    if carried and "planets" not in switches:       # Newton takes every mass the source carries
        raise InputError("switches", tuple(switches), f"'planets' among them with an orbit source that carries "
                                                      f"{carried}, or a source without the planets")
    planets = tuple(p for p in PLANETS if p in external.names) if "planets" in switches else ()
    moon, earth_ = moon_body("moon_distortion" in switches), earth_body()
    motion = Pair("earth", "moon", earth_.gm, moon.gm, "earth_moon_barycenter", external)
    orbit = [Newton()] + ([Relativity(c_km_d())] if "relativity" in switches else [])
    return System("earth-moon", [moon, earth_], motion, orbit + couplings() + solar(switches, planets), t0, start,
                  {"switches": tuple(switches)})


def closed(figures=tuple(FIGURES), t0=0.0, start=None, earth_rotator=None, moon_core=True):
    """The same Earth and Moon with no orbit source: the pair about its barycentre at rest; no dissipation
    (the Moon undistorted), only the ``figures`` (FIGURES' names) acting."""
    moon, earth_ = moon_body(distortion=False, core=moon_core), earth_body(earth_rotator)
    return System("earth-moon (closed)", [moon, earth_], Pair("earth", "moon", earth_.gm, moon.gm),
                  [Newton(), *couplings(figures)], t0, start, {"figures": tuple(figures)})
