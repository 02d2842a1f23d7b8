"""What DE421's asteroids, absent from the solar-system scene, move in each planet and in the Moon over 1950-2050.

Run: ``nice -n 10 python benchmarks/asteroid_share.py``.  DE421 integrated 343 asteroids (Folkner, Williams &
Boggs 2008); its header gives the masses of 67 (MA*, 9.5e-10 of the Sun's together), Ceres, Pallas and Vesta
7.0e-10 of them, but none of their states.  Here those three are added to DE421's model as point masses with
their DE421 masses, started from DE430's barycentric states at the same epoch (1969-06-28; Folkner et al. 2014,
as tabulated in PlanetaryEphemeris.jl's data/ast343ic_1969Jun28.txt, commit 621816028525), and each planet's
heliocentric position and the geocentric Moon are compared with the run without them.  The difference, times
9.5/7.0 for the other 64 of known mass, is the estimate of what the asteroids leave in a comparison with
DE421 (a lower bound for the 276 of class densities, unscaled).
"""
import sys
import time

import numpy as np

from spinorbit.base.constants import J2000_JD, MAS
from spinorbit.base.rotations import vector_angle
from spinorbit.bodies import earth
from spinorbit.bodies.de421_header import header
from spinorbit.integrators import simulate
from spinorbit.models.assemblies.solar_system import solar_system
from spinorbit.models.start import solar_system_de421
from spinorbit.references.erfa_pole import cip_vector
from spinorbit.scene.schema import parse_tdb_days

# DE430's barycentric states at JD 2440400.5 TDB (au, au/d, ICRF) and DE421's header mass key
STATES = {"ceres": ((1.4431843184611104, -2.203606556762316, -1.326131795443559,
                     0.008465054386780241, 0.004689425603745441, 0.0004683868407746507), "MA0001"),
          "vesta": ((0.18687434516205764, 2.387395287704745, 0.9248621207540324,
                     -0.010174848496655332, 4.6655816939785886e-5, 0.001346386736334536), "MA0004"),
          "pallas": ((0.20833478124693103, -3.208852359635216, 0.6241092369971604,
                      0.008533962106115175, -0.0008554815837133276, -0.00039067289039383435), "MA0002")}


def run(with_asteroids):
    h = header()
    t0 = h["JDEPOC"] - J2000_JD
    extra = tuple((name, h[key] * h["AU"] ** 3) for name, (_, key) in STATES.items()) if with_asteroids else ()
    system = solar_system(t0=t0, extra=extra)
    others = {}
    for name, (state, _) in (STATES.items() if with_asteroids else ()):
        others[f"{name}.r"], others[f"{name}.v"] = np.array(state[:3]) * h["AU"], np.array(state[3:]) * h["AU"]
    system.y0 = system.layout.pack(solar_system_de421(system, t0, cip_vector(t0), earth.ERA_RATE_RAD_D,
                                                      others=others))
    t = np.arange(parse_tdb_days("s", "1950-01-01T00:00:00"), parse_tdb_days("e", "2050-01-01T00:00:00") + 0.1, 4.0)
    started = time.perf_counter()
    solution, _ = simulate(system, t, "taylor", {"tolerance": 1e-15}, estimate_error=False, label=None)
    print(f"run with asteroids {with_asteroids}: {time.perf_counter() - started:.0f} s", file=sys.stderr)
    sun = solution.part("sun.r")
    share = system.motion.share
    earth_ = solution.part("earth_moon_barycenter.r") - share * solution.part("moon.r") - sun
    planets = {name: solution.part(f"{name}.r") - sun for name in ("mercury", "venus", "mars", "jupiter", "saturn",
                                                                    "uranus", "neptune", "pluto")}
    return t, {"earth": earth_, **planets, "moon": solution.part("moon.r")}


def against_de421(t, positions):
    """{body: max |x - DE421| km} and the Moon's direction (mas) and range (m) against DE421."""
    from spinorbit.comparisons.solar_system_de421 import orbit_errors, planet_errors

    errors = {name: float(e.max()) for name, e in planet_errors(t, {k: v for k, v in positions.items()
                                                                     if k != "moon"}).items()}
    direction, distance = orbit_errors(t, positions["moon"])
    return errors, float(direction.max() / MAS), float(np.abs(distance).max() * 1e3)


def main():
    h = header()
    known = sum(v for k, v in h.items() if k.startswith("MA") and k[2:].isdigit())
    scale = known / sum(h[key] for _, key in STATES.values())
    (t, without), (_, with_them) = run(False), run(True)
    off, off_dir, off_range = against_de421(t, without)
    on, on_dir, on_range = against_de421(t, with_them)
    print(f"| body | Ceres, Pallas, Vesta move it [km] | x {scale:.2f} [km] | DE421 - this [km] | DE421 - this with "
          "the three [km] |\n|---|---|---|---|---|")
    for name, x in without.items():
        if name != "moon":
            moved = float(np.linalg.norm(with_them[name] - x, axis=1).max())
            print(f"| {name} | {moved:.3g} | {moved * scale:.3g} | {off[name]:.3g} | {on[name]:.3g} |")
    r, r_with = without["moon"], with_them["moon"]
    direction = vector_angle(r, r_with).max() / MAS
    distance = np.abs(np.linalg.norm(r, axis=1) - np.linalg.norm(r_with, axis=1)).max() * 1e3
    print(f"\nThe Moon: the three move it by {direction:.3g} mas and {distance:.3g} m (x {scale:.2f}: "
          f"{direction * scale:.3g} mas, {distance * scale:.3g} m); against DE421 {off_dir:.3g} mas and "
          f"{off_range:.3g} m without them, {on_dir:.3g} mas and {on_range:.3g} m with them")


if __name__ == "__main__":
    main()
