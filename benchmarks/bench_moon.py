"""Error against run time for the Moon (default level 3: degree 2-4, core, tides) driven by DE421.

Run: ``python benchmarks/bench_moon.py [--years 150] [--numpy-years 10] [--level 3]``.

* rk8 at several steps and dop853 (compiled rhs) at several tolerances over
  1900-01-05 + ``--years``, outputs every 2 d (rk8's step is independent of them: dense
  output): wall time (compilation excluded), max attitude error (max of pole and
  longitude) against a converged run (rk8, h = 0.25 d) and against DE421;
* the ratio against scipy ``solve_ivp`` DOP853 with a NumPy right-hand side (the same
  rhs run with NUMBA_DISABLE_JIT=1, in a subprocess) at equal error, over ``--numpy-years``:
  the fastest run of each method reaching each error level.
Level 3 carries the core's state, so the splitting methods cannot run it; at
``--level 1`` or ``2`` (a rigid body under a torque) suzuki4, yoshida4 and strang run too.
Prints Markdown tables for benchmarks/RESULTS.md.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
SCENARIO = ROOT / "scenarios" / "moon_libration.toml"


CADENCE_D = 2.0          # output every 2 d, as the scenario
LEVELS_ARCSEC = (0.2, 0.002, 2e-5)    # ~1e-6, 1e-8, 1e-10 rad


LEVEL = [3]               # model level (--level)
SPLITTINGS = {"suzuki4": (2.0, 1.0, 0.5, 0.25, 0.125), "yoshida4": (2.0, 1.0, 0.5, 0.25, 0.125),
              "strang": (1.0, 0.25, 0.0625, 0.015625)}


def build(years):
    from dataclasses import replace

    import astropy.units as u

    from spinorbit.edge.scenarios import load_scenario
    from spinorbit.starts.moon import build_system

    scenario = load_scenario(SCENARIO)
    p = scenario.params
    span = replace(p.span, end=p.span.start + (years * u.yr).to_value(u.d), step=CADENCE_D)
    scenario = scenario.with_params(replace(p, span=span, model=replace(p.model, level=LEVEL[0])))
    system, _ = build_system(scenario.params, scenario.params.orbit.source)
    return scenario, system


def attitudes(solution):
    from spinorbit.analysis.librations import icrf_to_body

    return icrf_to_body(solution.quaternion)


def error_arcsec(m_a, m_b):
    from spinorbit.analysis.librations import pole_and_longitude_difference
    from spinorbit.base.constants import ARCSEC

    pole, lon = pole_and_longitude_difference(m_a, m_b)
    return float(max(np.abs(pole).max(), np.abs(lon).max()) / ARCSEC)


def numpy_run(years, rtol, out):
    """Child process (NUMBA_DISABLE_JIT=1): scipy DOP853 on the pure NumPy rhs."""
    from scipy.integrate import solve_ivp

    scenario, system = build(years)
    t_out = scenario.output_times()
    fun = lambda t, y: system.rhs(t, y, system.params)
    start = time.perf_counter()
    sol = solve_ivp(fun, (system.t0, t_out[-1]), system.y0, method="DOP853", t_eval=t_out,
                    rtol=rtol, atol=rtol * 1e-2)
    wall = time.perf_counter() - start
    np.savez(out, y=sol.y.T, wall=wall, nfev=sol.nfev)


def compiled_rows(years):
    from spinorbit.integrators import simulate
    from spinorbit.references.moon_de421 import orientation

    scenario, system = build(years)
    t_out = scenario.output_times()
    ref = orientation(t_out)[0]
    converged = attitudes(simulate(system, t_out, "rk8", {"step": 0.25}, estimate_error=False)[0])
    rows = []
    runs = [("rk8", dict(step=h)) for h in (6.0, 4.0, 3.0, 2.0, 1.0)]
    runs += [("dop853", dict(rtol=r, atol=r * 1e-2)) for r in (1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11)]
    if system.torque is not None:        # levels 1-2: a rigid body under a torque, the splittings run
        runs += [(name, dict(step=h)) for name, steps in SPLITTINGS.items() for h in steps]
    for method, options in runs:
        sol = simulate(system, t_out, method, options, estimate_error=False)[0]
        m = attitudes(sol)
        rows.append(dict(method=method + (" + numba rhs" if method == "dop853" else ""), options=options,
                         wall_s=sol.wall_s, nfev=sol.nfev, error_vs_converged_arcsec=error_arcsec(m, converged),
                         error_vs_de421_arcsec=error_arcsec(m, ref)))
    return rows, converged, t_out


def numpy_rows(years, converged_10):
    rows = []
    for rtol in (1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11):
        with tempfile.TemporaryDirectory() as tmp:
            out = Path(tmp) / "run.npz"
            env = {**os.environ, "NUMBA_DISABLE_JIT": "1"}
            subprocess.run([sys.executable, __file__, "--level", str(LEVEL[0]), "--child", str(years), str(rtol),
                            str(out)],
                           check=True, env=env, cwd=ROOT)
            data = np.load(out)
            from spinorbit.base.rotations import matrix_from_quat

            y = data["y"]
            m = np.array([matrix_from_quat(q / np.linalg.norm(q)).T for q in y[:, :4]])
            rows.append(dict(method="scipy DOP853 + NumPy rhs", options=dict(rtol=rtol), wall_s=float(data["wall"]),
                             nfev=int(data["nfev"]), error_vs_converged_arcsec=error_arcsec(m, converged_10)))
    return rows


def table(rows, title):
    lines = [f"**{title}**", "",
             "| method | options | wall [s] | rhs calls | error vs converged [\"] | error vs DE421 [\"] |",
             "|---|---|---|---|---|---|"]
    for r in rows:
        opts = ", ".join(f"{k}={v:g}" for k, v in r["options"].items())
        de = r.get("error_vs_de421_arcsec")
        lines.append(f"| {r['method']} | {opts} | {r['wall_s']:.3g} | {r['nfev']} | "
                     f"{r['error_vs_converged_arcsec']:.2g} | {'' if de is None else f'{de:.3g}'} |")
    return "\n".join(lines)


def level_table(rows):
    """Fastest run of each method reaching each error level, and scipy + NumPy's time over it."""
    from spinorbit.edge.bench import fastest_at

    names = list(dict.fromkeys(r["method"] for r in rows))
    lines = ["| error <= | " + " | ".join(names) + " |", "|---|" + "---|" * len(names)]
    for level in LEVELS_ARCSEC:
        best = fastest_at(rows, level, error="error_vs_converged_arcsec")
        base = best.get("scipy DOP853 + NumPy rhs")
        cells = ["-" if m not in best else f"{best[m]:.3g}" + (f" (x{base / best[m]:.0f})" if base else "")
                 for m in names]
        lines.append(f"| {level:g}\" ({level * 4.848e-6:.0e} rad) | " + " | ".join(cells) + " |")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--years", type=float, default=150.0)
    parser.add_argument("--numpy-years", type=float, default=10.0)
    parser.add_argument("--level", type=int, default=3)
    parser.add_argument("--child", nargs=3)
    parser.add_argument("--json")
    args = parser.parse_args()
    LEVEL[0] = args.level
    if args.child:
        return numpy_run(float(args.child[0]), float(args.child[1]), args.child[2])
    rows, _, _ = compiled_rows(args.years)
    print(table(rows, f"Moon level {args.level}, {args.years:g} yr from 1900-01-05, outputs every {CADENCE_D:g} d"))
    short, converged_short, _ = compiled_rows(args.numpy_years)
    slow = numpy_rows(args.numpy_years, converged_short)
    print()
    print(table(short + slow, f"Moon level {args.level}, {args.numpy_years:g} yr: compiled vs NumPy rhs"))
    print()
    print(level_table(short + slow))
    if args.json:
        Path(args.json).write_text(json.dumps({"long": rows, "short": short + slow}, indent=1))


if __name__ == "__main__":
    main()
