"""REBOUND (IAS15 + gr_full + Earth J2, from DE421's state) against DE421: the Moon's geocentric direction
and distance after 1, 10, 50 and 100 years (max over the span), the drift that limits REBOUND-driven Moon runs.

    python benchmarks/bench_rebound_drift.py

The suite checks 1 and 10 years (tests/orbits/test_nbody.py); the longer spans are measured here (minutes).
"""
from spinorbit.base.constants import ARCSEC
from spinorbit.orbits.nbody import moon_drift

if __name__ == "__main__":
    print("| span | direction max | distance max |\n|---|---|---|")
    for years in (1, 10, 50, 100):
        angle, distance = moon_drift(years)
        print(f"| {years} yr | {angle / ARCSEC:.2f}\" | {distance:.1f} km |")
