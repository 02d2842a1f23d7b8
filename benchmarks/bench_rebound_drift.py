"""REBOUND (IAS15 + gr_full + Earth J2, from DE421's state) against DE421: the Moon's geocentric direction
and distance after 1, 10, 50 and 100 years (max over the span), the drift that limits REBOUND-driven Moon runs.

    python benchmarks/bench_rebound_drift.py

The suite checks 1 and 10 years (tests/test_nbody.py); the longer spans are measured here (minutes).
"""
import numpy as np

from spinorbit.constants import ARCSEC, JULIAN_YEAR_D
from spinorbit.orbits.kernel import DE421Arrays
from spinorbit.orbits.nbody import ReboundOrbits


def moon_error(years):
    """Max angle (arcsec) and distance (km) between REBOUND's and DE421's geocentric Moon over ``years`` from J2000."""
    orbits = ReboundOrbits("earth", ("moon",), 0.0, years * JULIAN_YEAR_D)
    t = np.linspace(0.0, years * JULIAN_YEAR_D, int(100 * years) + 1)
    ours = orbits.positions(t)[:, 0]
    truth = DE421Arrays().relative_states("moon", "earth", t)[0]
    angle = np.arctan2(np.linalg.norm(np.cross(ours, truth), axis=1), (ours * truth).sum(1))
    return angle.max() / ARCSEC, np.linalg.norm(ours - truth, axis=1).max()


if __name__ == "__main__":
    print("| span | direction max | distance max |\n|---|---|---|")
    for years in (1, 10, 50, 100):
        angle, distance = moon_error(years)
        print(f"| {years} yr | {angle:.2f}\" | {distance:.1f} km |")
