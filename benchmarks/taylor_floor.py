"""The solar system's Taylor run (scenarios/solar_system.toml) forward from DE421's epoch to 2050: Mercury as two
samplings see it, and the floor of double precision against a run in long double.

    nice python benchmarks/taylor_floor.py          # ~10 min on a loaded 2-core machine

Prints (m, heliocentric Mercury, largest over 1969-2050): the run sampled every 20 d and every 30 d at their
shared days; runs at tolerances 1e-15, 1e-16, 1e-17 and in heyoka's high-accuracy mode against a long-double
run at 1e-19 (heyoka's ``fp_type``: 64-bit mantissa) from the same start.
"""
import functools

import numpy as np

from spinorbit.edge.scenarios import load_scenario
from spinorbit.integrators import simulate, taylor
from spinorbit.starts.solar_system import system as solar_system

END_D = 18262.5                 # 2050-01-01, TDB days from J2000


def mercury(system, states):
    return states[:, system.layout["mercury.r"]] - states[:, system.layout["sun.r"]]


def double(system, t, tolerance, high_accuracy=False):
    """Mercury (km) of a double-precision run to t (spinorbit's Taylor integrator)."""
    hy = taylor.heyoka()
    plain = hy.taylor_adaptive
    taylor._BUILT.clear()
    hy.taylor_adaptive = functools.partial(plain, high_accuracy=True) if high_accuracy else plain
    try:
        return mercury(system, simulate(system, t, "taylor", {"tolerance": tolerance}, estimate_error=False)[0].y)
    finally:
        hy.taylor_adaptive = plain


def long_double(system, t):
    """Mercury (km) of the same equations integrated by heyoka in long double."""
    factors = taylor.scales(system.layout, system.y0)
    variables, derivatives = system.expressions(factors)
    ta = taylor.heyoka().taylor_adaptive(list(zip(variables, derivatives)),
                                         np.array(system.y0 / factors, dtype=np.longdouble),
                                         tol=np.longdouble(1e-19), compact_mode=True, fp_type=np.longdouble,
                                         time=np.longdouble(system.t0))
    states = ta.propagate_grid(np.concatenate([[system.t0], t]).astype(np.longdouble))[5][1:]
    return mercury(system, np.asarray(states, dtype=float) * factors)


def largest(a, b):
    return float(np.linalg.norm(a - b, axis=1).max() * 1e3)


def main():
    system = solar_system(load_scenario("scenarios/solar_system.toml").params)
    t20 = system.t0 + np.arange(20.0, END_D - system.t0, 20.0)
    t30 = system.t0 + np.arange(30.0, END_D - system.t0, 30.0)
    every20, every30 = double(system, t20, 1e-15), double(system, t30, 1e-15)
    shared = np.intersect1d(t20, t30)
    gap = largest(every20[np.isin(t20, shared)], every30[np.isin(t30, shared)])
    print(f"sampled every 20 d and every 30 d, shared days: {gap:.3g} m")
    reference = long_double(system, t20)
    runs = {"1e-15": every20, "1e-16": double(system, t20, 1e-16), "1e-17": double(system, t20, 1e-17),
            "1e-15, high accuracy": double(system, t20, 1e-15, True),
            "1e-16, high accuracy": double(system, t20, 1e-16, True)}
    print("| run | vs long double, m |\n|---|---|")
    for name, run in runs.items():
        print(f"| {name} | {largest(run, reference):.3g} |")


if __name__ == "__main__":
    main()
