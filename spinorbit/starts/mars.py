"""Mars's System and its start: the rigid planet of spinorbit.bodies.mars (models.assemblies.planet) on the Sun
(and the planets) seen from Mars in a JPL ephemeris, or on the Sun's Kepler ellipse through DE421's state at the
start; started on the IAU 2015 pole and prime meridian (references.mars_iau2015) on its forced motion."""
import math

import numpy as np

from ..base.errors import ScenarioError
from ..bodies import mars

PLANETS = ("mercury", "venus", "earth", "moon", "jupiter", "saturn")   # direct torques (Uranus on: < 1e-4 of them)
MARGIN_D = 1.0        # the orbits sampled beyond the run: the Oppolzer terms difference the torque at t +- 1/64 d


def planet(c_mr2=mars.C_MR2):
    """Mars as the assembly takes it (bodies.mars, the GM of DE421's header), with polar moment ``c_mr2``."""
    from ..bodies.table import gm_km3_d2
    from ..models.assemblies.planet import Planet

    return Planet("mars", gm_km3_d2("mars"), mars.RADIUS_KM, mars.J2, mars.C22, c_mr2, mars.SATELLITES)


def mean_orbit_frame():
    """ICRF -> the J2000 mean orbit's frame (x: its ascending node on the ICRF equator, z: its pole): Rx(J) Rz(N)."""
    n, j = math.radians(mars.MEAN_ORBIT_NODE_DEG), math.radians(mars.MEAN_ORBIT_INCLINATION_DEG)
    rz = np.array([[math.cos(n), math.sin(n), 0.0], [-math.sin(n), math.cos(n), 0.0], [0.0, 0.0, 1.0]])
    rx = np.array([[1.0, 0.0, 0.0], [0.0, math.cos(j), math.sin(j)], [0.0, -math.sin(j), math.cos(j)]])
    return rx @ rz


def start_epoch(p):
    """mars.start in TDB days."""
    return p.mars.start


def orbits(p, t0):
    """The Sun (and with orbit.planets the planets) seen from Mars over the run and t0."""
    source = p.orbit.source
    bodies = ("sun",) + (PLANETS if p.orbit.planets else ())
    if source.analytic:
        if p.orbit.planets:
            raise ScenarioError("orbit.planets", True, f'false with orbit.source = "{source.name}" (a two-body '
                                                      "orbit carries the Sun alone)")
        return source.relative("mars", bodies, t0, t0)
    first, last = min(p.span.start, p.span.end, t0) - MARGIN_D, max(p.span.start, p.span.end, t0) + MARGIN_D
    return source.relative("mars", bodies, first, last, p.orbit.sample_step)


def geodesic():
    """De Sitter's precession of Mars on its J2000 mean orbit (models.assemblies.planet.geodesic_rate)."""
    from ..base.constants import DAY_S
    from ..bodies.de421_header import header
    from ..bodies.table import gm_km3_d2
    from ..models.assemblies.planet import geodesic_rate

    pole = mean_orbit_frame().T @ np.array([0.0, 0.0, 1.0])
    anomaly = (math.radians(mars.MEAN_ANOMALY_J2000_DEG), math.radians(mars.MEAN_MOTION_DEG_D))
    return geodesic_rate(gm_km3_d2("sun"), header()["CLIGHT"] * DAY_S, mars.MEAN_SEMI_MAJOR_AXIS_KM, pole,
                         mars.MEAN_ECCENTRICITY, anomaly)


def system(p, t0):
    """Mars of ``p`` not yet started."""
    from ..models.assemblies.planet import rigid_planet

    return rigid_planet(planet(p.mars.c_mr2), orbits(p, t0), p.mars.model, p.mars.satellites,
                        geodesic() if p.mars.geodesic_precession else None, t0)


def iau_start(t0):
    """(pole (3,), x axis hint (3,), w_z rad/d) of the IAU 2015 Mars at t0: the body x axis toward the axis of
    least moment (bodies.mars.A_AXIS_LONGITUDE_DEG east of the prime meridian), w_z = dW/dt + sin(delta) d alpha/dt
    (the 3-1-3 kinematics of (alpha + 90 deg, 90 deg - delta, W))."""
    from ..references import mars_iau2015

    h = 1e-3
    (ra, ra_h), (dec, _), (w, w_h) = mars_iau2015.angles([t0, t0 + h])
    pole = np.array([math.cos(dec) * math.cos(ra), math.cos(dec) * math.sin(ra), math.sin(dec)])
    node = np.array([-math.sin(ra), math.cos(ra), 0.0])
    longitude = w + math.radians(mars.A_AXIS_LONGITUDE_DEG)
    x = math.cos(longitude) * node + math.sin(longitude) * np.cross(pole, node)
    return pole, x, (w_h - w) / h + math.sin(dec) * (ra_h - ra) / h


def build(p):
    """Mars started at mars.start on the IAU 2015 pole and spin, on its forced motion; its prime meridian there
    in ``meta["prime_meridian_rad"]``."""
    from ..models.start import on_pole
    from ..references import mars_iau2015

    t0 = start_epoch(p)
    built = system(p, t0)
    pole, x_axis, spin_rate = iau_start(t0)
    built.y0 = built.layout.pack(on_pole(built, "mars", t0, pole, spin_rate, x_axis))
    built.meta["prime_meridian_rad"] = mars_iau2015.angles([t0])[2][0]     # what a gyroscopic state lacks
    return built


def restarted(p, start):
    """Mars of ``p`` started at a stored state ``start`` = (t0, y) (a continuous solution's extension)."""
    return system(p, float(start[0])).with_start(*start)
