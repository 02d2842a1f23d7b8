"""The Earth-Moon System of scene earth_moon_coupled (spinorbit.models.assemblies.earth_moon): the Sun, planets
and Earth-Moon barycentre sampled from orbit.source, the model's terms switched by its keys, started from DE421's
state at span.start (or at the nearest epoch DE421's lunar series covers), the Earth on its forced motion about
the IAU 2006/2000A pole at the Earth rotation angle's rate."""
import time

import numpy as np

from ..base.errors import ScenarioError
from ..models.assemblies.earth_moon import EXTERNAL, PLANETS, SWITCHES
from ..scene.params import key, table


@table
class EarthMoonTermsTable:
    """The Earth-Moon model's terms each switched by a key, shared by the scenes built on it (the coupled Earth and
    Moon, the solar system: models.assemblies.earth_moon.SWITCHES, which the solar system's derive from)."""

    relativity: bool = key(type=bool, default=True, help=SWITCHES["relativity"])
    earth_tides: bool = key(type=bool, default=True, help=SWITCHES["earth_tides"])
    moon_distortion: bool = key(type=bool, default=True, help=SWITCHES["moon_distortion"])
    geodesic: bool = key(type=bool, default=True, help=SWITCHES["geodesic"])
    planets_on_moon_figure: bool = key(type=bool, default=True, help=SWITCHES["planets_on_moon_figure"])
    sun_on_earth_j3_j4: bool = key(type=bool, default=True, help=SWITCHES["sun_on_earth_j3_j4"])


def switches(p):
    """The model's terms switched on by ``p.model`` (models.assemblies.earth_moon.SWITCHES); compare.tides_off
    refused without the Earth's tides."""
    on = tuple(name for name in SWITCHES if getattr(p.model, name))
    if p.compare.tides_off and "earth_tides" not in on:
        raise ScenarioError("compare.tides_off", True, "false when model.earth_tides is false")
    return on


def without_tides(on):
    """The switches ``on`` without the Earth's tides (compare.tides_off's twin)."""
    return tuple(name for name in on if name != "earth_tides")


def start_epoch(p):
    """span.start, or the nearest epoch of DE421's lunar series (TDB days) when it lies outside."""
    from ..bodies.de421_orientation import span

    first, last = span()
    return float(np.clip(p.span.start, first + 1.0, last - 1.0))


def external_bodies(p):
    """(the Sun, planets and EMB sampled from orbit.source over the span and the start, the sampling's wall
    time s)."""
    t0, (first, last) = start_epoch(p), p.span.bounds
    names = EXTERNAL if p.model.planets else tuple(n for n in EXTERNAL if n not in PLANETS)
    started = time.perf_counter()
    external = p.orbit.source.barycentric(names, min(first, t0) - 1.0, max(last, t0) + 1.0, p.orbit.step)
    return external, time.perf_counter() - started


def system(p, external, on):
    """The Earth-Moon System on ``external`` with the switches ``on``, started from DE421 at span.start (or at
    the nearest epoch its lunar series covers, integrated out from there)."""
    from ..bodies import earth
    from ..models.assemblies.earth_moon import solar_system
    from ..models.start import earth_moon_de421
    from ..references.erfa_pole import cip_vector

    t0 = start_epoch(p)
    built = solar_system(external, on, t0)
    built.y0 = built.layout.pack(earth_moon_de421(built, t0, cip_vector(t0), earth.ERA_RATE_RAD_D))
    return built


def started_at(p, start):
    """The Earth-Moon System of ``p`` started at a stored state ``start`` = (t0, y)."""
    from ..models.assemblies.earth_moon import solar_system

    on = tuple(name for name in SWITCHES if getattr(p.model, name))
    return solar_system(external_bodies(p)[0], on, float(start[0])).with_start(*start)


def closed_system(p):
    """The closed Earth-Moon System of scene coupled_conservation (models.assemblies.earth_moon.closed): the
    figures ``p.model`` switches on, the Earth gyroscopic or rigid (``model.earth_rotator``), the Moon rigid,
    started from DE421 at span.start."""
    from ..bodies import earth
    from ..models.assemblies.earth_moon import FIGURES, closed
    from ..models.rotators import Rigid
    from ..models.start import earth_moon_de421
    from ..references.erfa_pole import cip_vector

    t0 = p.span.start
    rotator = Rigid() if p.model.earth_rotator == "rigid" else None
    built = closed(tuple(name for name in FIGURES if getattr(p.model, name)), t0, earth_rotator=rotator,
                   moon_core=False)
    built.y0 = built.layout.pack(earth_moon_de421(built, t0, cip_vector(t0), earth.ERA_RATE_RAD_D))
    return built
