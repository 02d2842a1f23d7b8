"""What DE421's asteroids, absent from the solar-system scene, move in each planet over 1950-2050: an estimate.

Run: ``nice -n 10 python benchmarks/asteroid_share.py``.  DE421 integrated 343 asteroids (Folkner, Williams &
Boggs 2008); its header gives the masses of 67 (MA*, 9.5e-10 of the Sun's together), Ceres, Pallas and Vesta
7.0e-10 of them.  Here those three are added to DE421's model as point masses (their header masses, on orbits
from their osculating elements at J2000, rounded, ecliptic; DE421's epoch phases unknown here, so two sets of
mean anomalies are tried) and each planet's heliocentric position is compared with the run without them.  The
difference, times 9.5/7.0 for the other 64 of known mass (the rest, of class densities, unscaled), is the
estimate of what the asteroids leave in a comparison with DE421; the spread of the two phase sets says how
rough it is.
"""
import math
import sys
import time

import numpy as np

from spinorbit.bodies import earth
from spinorbit.bodies.de421_header import header
from spinorbit.constants import J2000_JD
from spinorbit.models.assemblies.solar_system import solar_system
from spinorbit.models.start import solar_system_de421
from spinorbit.references.erfa_pole import cip_vector
from spinorbit.schema import parse_tdb_days
from spinorbit.simulate import simulate

# a (au), e, i, node, argument of perihelion (deg), J2000 ecliptic; header mass key
ELEMENTS = {"ceres": (2.7675, 0.0760, 10.59, 80.31, 73.60, "MA0001"),
            "pallas": (2.7730, 0.2300, 34.84, 173.02, 310.05, "MA0002"),
            "vesta": (2.3615, 0.0887, 7.14, 103.81, 150.73, "MA0004")}
PHASES = {"A": (0.0, 120.0, 240.0), "B": (180.0, 300.0, 60.0)}       # mean anomalies at DE421's epoch, deg
OBLIQUITY = math.radians(84381.406 / 3600)                            # J2000 (IAU 2006)


def heliocentric_state(a_au, e, i, node, peri, mean_anomaly, gm):
    """(position km, velocity km/d) in ICRF axes of a Kepler orbit about GM (km^3/d^2) from ecliptic elements."""
    a = a_au * header()["AU"]
    big_e = mean_anomaly
    for _ in range(50):
        big_e -= (big_e - e * math.sin(big_e) - mean_anomaly) / (1 - e * math.cos(big_e))
    n = math.sqrt(gm / a ** 3)
    b = a * math.sqrt(1 - e * e)
    p = np.array([a * (math.cos(big_e) - e), b * math.sin(big_e), 0.0])
    v = np.array([-a * math.sin(big_e), b * math.cos(big_e), 0.0]) * n / (1 - e * math.cos(big_e))
    rz = lambda x: np.array([[math.cos(x), -math.sin(x), 0], [math.sin(x), math.cos(x), 0], [0, 0, 1]])
    rx = lambda x: np.array([[1, 0, 0], [0, math.cos(x), -math.sin(x)], [0, math.sin(x), math.cos(x)]])
    turn = rx(OBLIQUITY) @ rz(math.radians(node)) @ rx(math.radians(i)) @ rz(math.radians(peri))
    return turn @ p, turn @ v


def run(extra_phases=None):
    h = header()
    t0 = h["JDEPOC"] - J2000_JD
    extra = () if extra_phases is None else tuple((name, h[key] * h["AU"] ** 3)
                                                  for name, (*_, key) in ELEMENTS.items())
    system = solar_system(t0=t0, extra=extra)
    others = {}
    if extra_phases is not None:
        sun_x = np.array([h["XS"], h["YS"], h["ZS"]]) * h["AU"]
        sun_v = np.array([h["XDS"], h["YDS"], h["ZDS"]]) * h["AU"]
        for (name, (a, e, i, node, peri, _)), m in zip(ELEMENTS.items(), extra_phases):
            x, v = heliocentric_state(a, e, i, node, peri, math.radians(m), system.motion.gm("sun"))
            others[f"{name}.r"], others[f"{name}.v"] = sun_x + x, sun_v + v
    system.y0 = system.layout.pack(solar_system_de421(system, t0, cip_vector(t0), earth.ERA_RATE_RAD_D,
                                                      others=others))
    t = np.arange(parse_tdb_days("s", "1950-01-01T00:00:00"), parse_tdb_days("e", "2050-01-01T00:00:00") + 0.1, 4.0)
    started = time.perf_counter()
    solution, _ = simulate(system, t, "taylor", {"tolerance": 1e-15}, estimate_error=False, label=None)
    print(f"run {extra_phases}: {time.perf_counter() - started:.0f} s", file=sys.stderr)
    sun = solution.part("sun.r")
    share = system.motion.share
    earth_ = solution.part("earth_moon_barycenter.r") - share * solution.part("moon.r") - sun
    planets = {name: solution.part(f"{name}.r") - sun for name in ("mercury", "venus", "mars", "jupiter", "saturn",
                                                                    "uranus", "neptune", "pluto")}
    return {"earth": earth_, **planets, "moon": solution.part("moon.r")}


def main():
    h = header()
    known = sum(v for k, v in h.items() if k.startswith("MA") and k[2:].isdigit())
    three = sum(h[key] for *_, key in ELEMENTS.values())
    without = run()
    print(f"| body | {' | '.join(f'phases {k} [km]' for k in PHASES)} | x {known / three:.2f}: estimate [km] |")
    print("|---|---|---|---|")
    rows = {}
    for label, phases in PHASES.items():
        with_them = run(phases)
        for name, x in without.items():
            rows.setdefault(name, []).append(float(np.linalg.norm(with_them[name] - x, axis=1).max()))
    for name, values in rows.items():
        print(f"| {name} | {' | '.join(f'{v:.3g}' for v in values)} | {max(values) * known / three:.3g} |")


if __name__ == "__main__":
    main()
