"""Latency of the command line, in units of B, measured side by side in one run.

B = the wall time of a fresh Python importing numpy, scipy.integrate, astropy.table,
astropy.time and matplotlib.pyplot: what any run of a scientific Python tool pays
before it computes.  Measured, interleaved so that machine load falls on both alike:

* ``spinorbit --help`` and ``spinorbit list``;
* the main job, ``spinorbit run scenarios/moon_libration.toml``, warm (numba's and
  spinorbit's kernel caches filled by an earlier run) and cold (both empty).

    python benchmarks/bench_latency.py [--repeat 3]

prints a Markdown table for benchmarks/RESULTS.md: the minimum and the median seconds of each row
and their ratios to B's minimum and median (on a machine shared with other work, the minimum is the
figure least disturbed by it; the cold run is timed once).
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
IMPORTS_B = "import numpy, scipy.integrate, astropy.table, astropy.time, matplotlib.pyplot"
MAIN_JOB = "scenarios/moon_libration.toml"


def timed(command, env):
    start = time.perf_counter()
    subprocess.run(command, cwd=ROOT, env=env, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def environment(cache):
    env = dict(os.environ, NUMBA_CACHE_DIR=str(cache / "numba"), SPINORBIT_CACHE_DIR=str(cache / "spinorbit"),
               SPINORBIT_QUIET="1")
    return env


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    cli = [sys.executable, "-m", "spinorbit.edge.cli"]
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        warm = environment(tmp / "warm")
        out = ["--out", str(tmp / "run")]
        timed(cli + ["run", MAIN_JOB, *out], warm)                     # fill the caches
        rows = {"B (imports)": [], "spinorbit --help": [], "spinorbit list": [], "main job, warm": [],
                "main job, cold": []}
        for k in range(args.repeat):
            rows["B (imports)"].append(timed([sys.executable, "-c", IMPORTS_B], warm))
            rows["spinorbit --help"].append(timed(cli + ["--help"], warm))
            rows["spinorbit list"].append(timed(cli + ["list"], warm))
            rows["main job, warm"].append(timed(cli + ["run", MAIN_JOB, *out], warm))
            if k == 0:                                                  # ~30 s: once
                rows["main job, cold"].append(timed(cli + ["run", MAIN_JOB, *out], environment(tmp / f"cold{k}")))
    b_min, b_median = min(rows["B (imports)"]), statistics.median(rows["B (imports)"])
    targets = {"spinorbit --help": 1, "spinorbit list": 1, "main job, warm": 3, "main job, cold": 6}
    print("| what | min s | ratio to B (min) | median s | ratio to B (median) | target |\n|---|---|---|---|---|---|")
    for name, times in rows.items():
        low, median = min(times), statistics.median(times)
        target = f"<= {targets[name]} B" if name in targets else ""
        print(f"| {name} | {low:.2f} | {low / b_min:.2f} | {median:.2f} | {median / b_median:.2f} | {target} |")


if __name__ == "__main__":
    main()
