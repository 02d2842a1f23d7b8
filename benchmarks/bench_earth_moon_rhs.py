"""The cost of one evaluation of the coupled Earth-Moon right-hand side (the System of
spinorbit.models.assemblies.earth_moon, generated), in a compiled loop as the integrator calls it, at DE421's
state of 1950-01-01 (the coupled scene's start) with every switch on; times spread over the following 30 days.
Compilation is done before timing.

    python benchmarks/bench_earth_moon_rhs.py [--calls 200000] [--repeat 7]

prints the minimum and the median over the repeats, microseconds per evaluation.
"""
import argparse
import statistics
import time

from numba import njit

from spinorbit.bodies import earth
from spinorbit.models.assemblies.earth_moon import EXTERNAL, solar_system
from spinorbit.models.start import earth_moon_de421
from spinorbit.orbits.sources import barycentric
from spinorbit.references.erfa_pole import cip_vector

T0 = -18262.5           # 1950-01-01 TDB, days from J2000


@njit
def _loop(rhs, p, y, t0, n):
    acc = 0.0
    for i in range(n):
        acc += rhs(t0 + 30.0 * i / n, y, p)[3]
    return acc


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=200_000)
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    system = solar_system(barycentric("de421", EXTERNAL, T0 - 1.0, T0 + 31.0), t0=T0)
    y, p = system.layout.pack(earth_moon_de421(system, T0, cip_vector(T0), earth.ERA_RATE_RAD_D)), system.params
    _loop(system.rhs, p, y, T0, 1)
    times = []
    for _ in range(args.repeat):
        start = time.perf_counter()
        _loop(system.rhs, p, y, T0, args.calls)
        times.append((time.perf_counter() - start) / args.calls * 1e6)
    print(f"earth-moon rhs: {min(times):.2f} us per evaluation (min of {args.repeat} x {args.calls}; "
          f"median {statistics.median(times):.2f})")


if __name__ == "__main__":
    main()
