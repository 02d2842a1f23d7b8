"""Does an edit recompile only the kernels it reaches, and every one it reaches? Wall time of one run, cold,
warm, then after an edit.

    python benchmarks/bench_cache_reach.py [--scenario scenarios/moon_libration.toml] [--repeat 3]
                                           [--baseline GIT_REF]

A copy of the package (this tree's, and with ``--baseline`` the package at a git ref, e.g. one whose linker
fingerprinted every file) runs the scenario in fresh processes with its own empty kernel and numba caches:
once to fill them (cold), ``--repeat`` times warm, then after adding a line to the docstring of a module no
kernel reaches (``spinorbit/scene/verdict.py``), then after the same edit in a module the kernels reach
(``spinorbit/base/rotations.py``), each step on every tree in turn. Printed: the median wall time of each, how many
generated modules were written (a recompiled kernel writes its module anew) and how many numba cache indexes
of the package's own compiled functions were written (a function compiled afresh rewrites its index; one that
calls an edited file and is not rewritten runs its old code).
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
UNREACHED, REACHED = "spinorbit/scene/verdict.py", "spinorbit/base/rotations.py"
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


def package_trees(work, baseline):
    """[(label, root)]: this tree's package, and the one at git ``baseline`` beside it when given."""
    trees = [("this tree", copy_package(work, None))]
    if baseline:
        trees.append((baseline, copy_package(work, baseline)))
    return trees


def run(tree, scenario, work):
    """Wall time (s) of one run in a fresh process, the generated modules in the kernel cache and numba's
    indexes of the package's functions ({path: modification time})."""
    cache = work / f"cache-{tree.name}"
    env = {**os.environ, "PYTHONPATH": str(tree), "SPINORBIT_CACHE_DIR": str(cache),
           "NUMBA_CACHE_DIR": str(work / f"numba-{tree.name}"), "SPINORBIT_QUIET": "1"}
    start = time.perf_counter()               # run outside the tree: `-m` puts the working directory first
    subprocess.run([sys.executable, "-m", "spinorbit.edge.cli", "run", str(scenario), "--out", str(work / "out"),
                    "--force", *SHORT], cwd=work, env=env, check=True, capture_output=True)
    wall = time.perf_counter() - start
    indexes = {p: p.stat().st_mtime_ns for p in (work / f"numba-{tree.name}").rglob("*.nbi")}
    return wall, sorted(p.name for p in cache.rglob("spinorbit_*.py")), indexes


def touch_docstring(path):
    text = path.read_text()
    end = text.index('"""', 3)
    path.write_text(text[:end] + f"\nEdited at {time.time()}.\n" + text[end:])


def measure(trees, scenario, work, repeat):
    """{row: {tree: (wall s, generated modules written, numba indexes written)}}, each step run on every tree in
    turn, so that the trees share the machine's load."""
    seen, rows = {}, {"cold (empty caches)": {}, "warm": {}}
    for name, tree in trees:                                        # fill the caches
        wall, modules, indexes = run(tree, scenario, work)
        rows["cold (empty caches)"][name] = (wall, len(modules), len(indexes))
        seen[name] = modules, indexes
    warm = {name: [] for name, _ in trees}
    for _ in range(repeat):
        for name, tree in trees:
            warm[name].append(run(tree, scenario, work)[0])
    rows["warm"] = {name: (statistics.median(walls), 0, 0) for name, walls in warm.items()}
    for label, module in ((f"after editing {Path(UNREACHED).name} (no kernel reaches it)", UNREACHED),
                          (f"after editing {Path(REACHED).name} (the kernels reach it)", REACHED)):
        rows[label] = {}
        for name, tree in trees:
            touch_docstring(tree / module)
            wall, after, written = run(tree, scenario, work)
            modules, indexes = seen[name]
            rows[label][name] = (wall, len(set(after) - set(modules)),
                                 sum(indexes.get(path) != stamp for path, stamp in written.items()))
            seen[name] = after, written
    return rows


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--scenario", default=str(ROOT / "scenarios" / "moon_libration.toml"))
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--baseline", help="git ref of a package to measure beside this tree's")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        work = Path(tmp)
        trees = package_trees(work, args.baseline)
        settings = " ".join(SHORT[1::2])
        print(f"{Path(args.scenario).name} {settings}; wall s of one run (generated modules, numba indexes "
              "written)")
        for label, cells in measure(trees, args.scenario, work, args.repeat).items():
            print(f"  {label:45s} " + "   ".join(f"{name}: {wall:6.2f} s ({modules}, {indexes})"
                                               for name, (wall, modules, indexes) in cells.items()))


if __name__ == "__main__":
    main()
