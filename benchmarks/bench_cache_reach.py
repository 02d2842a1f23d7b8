"""Does an edit recompile only the kernels it reaches?  Wall time of one run, warm, then after an edit.

    python benchmarks/bench_cache_reach.py [--scenario scenarios/moon_libration.toml] [--repeat 3]
                                           [--baseline GIT_REF]

A copy of the package (this tree's, and with ``--baseline`` the package at a git ref, e.g. one whose
linker fingerprinted every file) runs the scenario in fresh processes with its own empty kernel and
numba caches: once to fill them, ``--repeat`` times warm, then after adding a line to the docstring
of a module no kernel reaches (``spinorbit/verdict.py``), then after the same edit in a module the
kernels reach (``spinorbit/rotations.py``).  Printed: the median wall time of each and how many
generated modules were written (a recompiled kernel writes its module anew).
"""
import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
UNREACHED, REACHED = "spinorbit/verdict.py", "spinorbit/rotations.py"
SHORT = ["--set", "span.end=20 d", "--set", "output.plots=false", "--set", "integrator.estimate_error=false"]


def copy_package(work, ref):
    """A copy of the package (this tree's, or the one at git ``ref``) under ``work``; returns its root."""
    tree = work / (ref or "tree").replace("/", "_")
    if ref is None:
        shutil.copytree(ROOT / "spinorbit", tree / "spinorbit", ignore=shutil.ignore_patterns("__pycache__"))
    else:
        tree.mkdir()
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", ref, "spinorbit"], check=True,
                                 capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", str(tree)], input=archive, check=True)
    return tree


def run(tree, scenario, work):
    """Wall time (s) of one run in a fresh process, and the generated modules in the kernel cache."""
    cache = work / f"cache-{tree.name}"
    env = {**os.environ, "PYTHONPATH": str(tree), "SPINORBIT_CACHE_DIR": str(cache),
           "NUMBA_CACHE_DIR": str(work / f"numba-{tree.name}"), "SPINORBIT_QUIET": "1"}
    start = time.perf_counter()               # run outside the tree: `-m` puts the working directory first
    subprocess.run([sys.executable, "-m", "spinorbit.cli", "run", str(scenario), "--out", str(work / "out"),
                    "--force", *SHORT], cwd=work, env=env, check=True, capture_output=True)
    wall = time.perf_counter() - start
    return wall, sorted(p.name for p in cache.rglob("spinorbit_*.py"))


def touch_docstring(path):
    text = path.read_text()
    end = text.index('"""', 3)
    path.write_text(text[:end] + f"\nEdited at {time.time()}.\n" + text[end:])


def measure(tree, scenario, work, repeat):
    rows = {}
    modules = run(tree, scenario, work)[1]                          # fill the caches
    rows["warm"] = (statistics.median(run(tree, scenario, work)[0] for _ in range(repeat)), 0)
    for label, module in ((f"after editing {Path(UNREACHED).name} (no kernel reaches it)", UNREACHED),
                          (f"after editing {Path(REACHED).name} (the kernels reach it)", REACHED)):
        touch_docstring(tree / module)
        wall, after = run(tree, scenario, work)
        rows[label] = (wall, len(set(after) - set(modules)))
        modules = after
    return rows


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--scenario", default=str(ROOT / "scenarios" / "moon_libration.toml"))
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--baseline", help="git ref of a package to measure beside this tree's")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        trees = [("this tree", copy_package(work, None))]
        if args.baseline:
            trees.append((args.baseline, copy_package(work, args.baseline)))
        settings = " ".join(SHORT[1::2])
        print(f"{Path(args.scenario).name} {settings}; wall s of one run (modules compiled anew)")
        results = {name: measure(tree, args.scenario, work, args.repeat) for name, tree in trees}
        for label in next(iter(results.values())):
            cells = "   ".join(f"{name}: {r[label][0]:6.2f} s ({r[label][1]})" for name, r in results.items())
            print(f"  {label:45s} {cells}")


if __name__ == "__main__":
    main()
