"""The solar system of scene solar_system (spinorbit.models.assemblies.solar_system): DE421's model with the
terms its keys switch, started from DE421's initial conditions at its epoch JDEPOC (or its states at span.start,
``start.epoch = "span"``), the Earth on its forced motion about the IAU 2006/2000A pole."""
from ..models.assemblies.solar_system import SWITCHES


def switches(p):
    """The model's terms switched on by ``p.model`` (models.assemblies.solar_system.SWITCHES)."""
    return tuple(name for name in SWITCHES if getattr(p.model, name))


def start_epoch(p):
    """TDB days of the run's start: DE421's epoch JDEPOC, or span.start."""
    from ..base.constants import J2000_JD
    from ..bodies.de421_header import header

    return header()["JDEPOC"] - J2000_JD if p.start.epoch == "de421" else p.span.start


def own_start(p):
    """span.start with ``start.epoch = "span"``, or None: the stored solution's anchor, DE421's epoch."""
    return p.span.start if p.start.epoch == "span" else None


def nbody_counts(p):
    """The days the Taylor integrator follows for the up-front estimate (its steps are its own: it is
    counted by the day), from the start epoch both ways over the span, twice when its error is estimated."""
    if p.integrator.method != "taylor":
        return {}
    t0 = start_epoch(p)
    days = max(p.span.start, p.span.end, t0) - min(p.span.start, p.span.end, t0)
    return {"Taylor days (solar system)": days * (2 if p.integrator.estimate_error else 1)}


def system(p):
    """DE421's solar system with the switches of ``p``, started as ``start.epoch`` says."""
    from ..bodies import earth
    from ..models.assemblies.solar_system import solar_system
    from ..models.start import solar_system_de421
    from ..references.erfa_pole import cip_vector

    t0 = start_epoch(p)
    built = solar_system(switches(p), t0)
    built.y0 = built.layout.pack(solar_system_de421(built, t0, cip_vector(t0), earth.ERA_RATE_RAD_D))
    return built


def started_at(p, start):
    """The solar system of ``p`` started at a stored state ``start`` = (t0, y)."""
    from ..models.assemblies.solar_system import solar_system

    return solar_system(switches(p), float(start[0])).with_start(*start)
