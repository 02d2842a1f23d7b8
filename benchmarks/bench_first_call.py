"""The first call of compiled equations whose callees live in other files: cold, warm, and after an edit of a
file they reach, this tree beside a git ref.

    python benchmarks/bench_first_call.py [--baseline GIT_REF] [--repeat 3]

Each step runs on every tree in turn (the same load); each call is timed in a fresh process on a copy of the
package (bench_cache_reach.copy_package) with its own numba cache (NUMBA_CACHE_DIR): ``deep_time.rhs`` (the
averaged spin equations: ``rotations`` is its callees' file) and ``tidal_history.equations.rhs`` (the Earth-
Moon history's: ``tidal_history/response.py`` among its callees' files; timed from its tide's calibration,
which calls it first), each on the arguments of a run. Rows: cold (empty cache: compiled), warm (the median of
``--repeat``: loaded), then after a line added to the docstring of the callees' file: compiled again where the
cache is keyed by what the function reaches (``linker.cached``), loaded where numba stamps the caller's own
file only (then an edit of the callee's code would run the old code).
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

from bench_cache_reach import package_trees, touch_docstring

FIRST_CALLS = """
import time
import numpy as np
from spinorbit.models import deep_time
from spinorbit.models.tidal_history import equations
from spinorbit.starts import earth_moon_history as history

grid = np.tile([0.0, 0.0, 1.0, 0.0167, 0.0, 0.0], (8, 1))
p = deep_time.parameters(grid, 0.0, 1000.0, 1.4e-7, 0.0167, 1.496e8, 2.59e10, 6.3)
start = time.perf_counter()
deep_time.rhs(10.0, np.array([0.0, 0.398, 0.917, 1.0, 1.0]), p)
deep = time.perf_counter() - start
start = time.perf_counter()               # the calibration of the tide calls the rhs first
c = history.constants(2.89)
y0 = history.today(c)
system = equations.history(c, history.tide({"tides.recession_rate": 3.83}, c, y0, "constant_time_lag"), y0)
system.rhs(system.t0, system.y0, system.params)
print(deep, time.perf_counter() - start)
"""
KERNELS = ("deep_time.rhs", "tidal_history.equations.rhs")
EDITS = (("rotations.py", "spinorbit/base/rotations.py"), ("tidal_history/response.py",
                                                      "spinorbit/models/tidal_history/response.py"))


def first_calls(tree, work):
    """Seconds of each kernel's first call in a fresh process on ``tree``'s own numba cache."""
    env = {**os.environ, "PYTHONPATH": str(tree), "SPINORBIT_CACHE_DIR": str(work / f"cache-{tree.name}"),
           "NUMBA_CACHE_DIR": str(work / f"numba-{tree.name}"), "SPINORBIT_QUIET": "1"}
    done = subprocess.run([sys.executable, "-c", FIRST_CALLS], cwd=work, env=env, check=True,
                          capture_output=True, text=True)
    return [float(value) for value in done.stdout.split()]


def measure(trees, work, repeat):
    """{row: {tree: [seconds of each kernel's first call]}}, each step run on every tree in turn, so that the
    trees share the machine's load."""
    rows = {"cold (empty cache)": {name: first_calls(tree, work) for name, tree in trees}}
    warm = {name: [] for name, _ in trees}
    for _ in range(repeat):
        for name, tree in trees:
            warm[name].append(first_calls(tree, work))
    rows["warm (median)"] = {name: [statistics.median(c) for c in zip(*calls)] for name, calls in warm.items()}
    for label, path in EDITS:
        rows[f"after editing {label}"] = {}
        for name, tree in trees:
            touch_docstring(tree / path)
            rows[f"after editing {label}"][name] = first_calls(tree, work)
    return rows


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--baseline", help="git ref of a package to measure beside this tree's")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        trees = package_trees(work, args.baseline)
        rows = measure(trees, work, args.repeat)
    print("first call, s: " + "   ".join(f"{name}: " + " / ".join(KERNELS) for name, _ in trees))
    for label, cells in rows.items():
        print(f"  {label:40s} " + "   ".join(" / ".join(f"{s:6.3f}" for s in calls) for calls in cells.values()))


if __name__ == "__main__":
    main()
