"""The coupled Earth-Moon run against the one-way DE421-driven Moon run, side by side, and its error
against run time.

* cost: ``spinorbit run scenarios/earth_moon_coupled.toml`` (1950-2050) beside ``spinorbit run
  scenarios/moon_libration.toml`` over the same span, both warm (caches filled by an earlier run),
  interleaved so that machine load falls on both alike; the wall time of each whole command and of its
  integration (summary ``run.wall_s``), and their ratio;
* error against run time: the coupled scene at RK8 steps ``--steps`` (days), each with its integration
  wall time and its errors against DE421 (Moon direction, range, lunar pole, longitude).

    python benchmarks/bench_coupled.py [--repeat 2] [--steps 1 0.5 0.4 0.25]

prints Markdown tables for benchmarks/RESULTS.md.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SPAN = ['span.start="1950-01-01T00:00:00"', 'span.end="2050-01-01T00:00:00"']
COUPLED, ONE_WAY = "scenarios/earth_moon_coupled.toml", "scenarios/moon_libration.toml"
ERRORS = (("moon_direction_error_max_arcsec", "direction ″"), ("moon_range_error_max_km", "range km"),
          ("pole_error_max_arcsec", "pole ″"), ("longitude_error_max_arcsec", "longitude ″"))


def run(scenario, out, env, extra=()):
    """(wall s of the whole command, its summary)."""
    sets = [a for s in (*SPAN, *extra) for a in ("--set", s)]
    start = time.perf_counter()
    subprocess.run([sys.executable, "-m", "spinorbit.edge.cli", "run", scenario, "--out", str(out), *sets],
                   cwd=ROOT, env=env, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    return wall, json.loads((out / "summary.json").read_text())


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=2)
    parser.add_argument("--steps", type=float, nargs="+", default=[1.0, 0.5, 0.4, 0.25])
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        env = dict(os.environ, NUMBA_CACHE_DIR=str(tmp / "numba"), SPINORBIT_CACHE_DIR=str(tmp / "spinorbit"),
                   SPINORBIT_QUIET="1")
        for scenario in (COUPLED, ONE_WAY):
            run(scenario, tmp / "warmup", env)                           # fill the caches
        walls = {COUPLED: [], ONE_WAY: []}
        for _ in range(args.repeat):
            for scenario in (COUPLED, ONE_WAY):
                wall, summary = run(scenario, tmp / "side", env)
                walls[scenario].append((wall, summary["run"]["wall_s"]))
        ladder = []
        for step in args.steps:
            wall, summary = run(COUPLED, tmp / f"step{step}", env, [f'integrator.step="{step} d"'])
            ladder.append((step, summary["run"]["wall_s"], wall, summary["comparison"]))
    best = {name: min(w) for name, w in walls.items()}
    print("| 1950-2050, warm | whole command s | integration s |\n|---|---|---|")
    for name, label in ((ONE_WAY, "one-way: Moon driven by DE421 (level 3)"), (COUPLED, "coupled Earth-Moon")):
        print(f"| {label} | {best[name][0]:.1f} | {best[name][1]:.1f} |")
    print(f"| **ratio coupled / one-way** | **{best[COUPLED][0] / best[ONE_WAY][0]:.2f}** | "
          f"{best[COUPLED][1] / best[ONE_WAY][1]:.2f} |")
    print(f"\nmin of {args.repeat}, interleaved; medians {statistics.median(w[0] for w in walls[COUPLED]):.1f} s "
          f"and {statistics.median(w[0] for w in walls[ONE_WAY]):.1f} s\n")
    print("| RK8 step d | integration s | whole command s | " + " | ".join(t for _, t in ERRORS) + " |")
    print("|---" * (3 + len(ERRORS)) + "|")
    for step, integration, wall, comparison in ladder:
        print(f"| {step:g} | {integration:.1f} | {wall:.1f} | "
              + " | ".join(f"{comparison[k]:.3g}" for k, _ in ERRORS) + " |")


if __name__ == "__main__":
    main()
