"""Mercury's spin started in its Cassini state (scenes/mercury_spin): the orbit from the scenario's source, its
node precession scaled when asked (the orbit turned about k x dk/dt, spinorbit.orbits.interpolant.turned), the
body's interior from the parameters, the System and its start from spinorbit.analysis.resonant_spin."""
import math

from ..base.errors import ScenarioError
from ..bodies import mercury


def interior(p):
    """The Interior of the parameters (J2 and C22 from bodies.mercury unless set)."""
    from ..analysis.resonant_spin import Interior

    return Interior(p.body.j2, p.body.c22, p.body.c_mr2, p.body.cm_over_c, p.core.coupling_time)


def model(p, times, scale=1.0):
    """(System, context) started in the Cassini state, on the orbit with its node precession x ``scale``."""
    import numpy as np

    from ..analysis.resonant_spin import cassini_system, mean_orbit
    from ..bodies.table import gm_km3_d2
    from ..orbits.interpolant import turned
    t0, t1 = float(min(times)), float(max(times))
    orbits = p.orbit.source.relative("mercury", ("sun",), t0, t1, p.orbit.step)
    gm = gm_km3_d2("sun") + gm_km3_d2("mercury")
    if scale != 1.0:
        orbit = mean_orbit(orbits, t0, t1, gm)
        orbits = turned(orbits, (scale - 1.0) * np.cross(orbit.normal, orbit.normal_rate), t0)
    return cassini_system(orbits, interior(p), p.span.start, t1 if p.span.start == t0 else t0, gm,
                          math.radians(mercury.LAPLACE_INCLINATION_DEG), p.start.obliquity_offset)


def scales(p):
    """The precession scales asked, checked: numbers in [0, 10]."""
    given = p.precession.scales
    if not all(isinstance(s, (int, float)) and not isinstance(s, bool) and 0 <= s <= 10 for s in given):
        raise ScenarioError("precession.scales", given, "a list of numbers in [0, 10], e.g. [0, 0.5, 2]")
    return [float(s) for s in given]
