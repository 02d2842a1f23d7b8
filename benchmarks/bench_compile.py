"""Where a cold run's numba compilation goes: seconds per compiled function, from numba's event API.

    python benchmarks/bench_compile.py [scenario.toml] [--top 25]

runs the scenario (default: the main job) in this process with empty numba and spinorbit kernel caches
and prints, per function, the seconds spent compiling it *without* the functions it compiled on the
way (exclusive), the part of those spent in LLVM (optimisation and machine code), and how many
specialisations it got.  A library links all it calls and is optimised whole, so a function's
exclusive LLVM time grows with the tree below it.
"""
import argparse
import os
import sys
import tempfile
import time
from collections import defaultdict
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


class CompileTimes:
    """Listener of numba's "numba:compile" and "numba:llvm_lock" events: exclusive seconds per function."""

    def __init__(self):
        self.total, self.llvm, self.count = defaultdict(float), defaultdict(float), defaultdict(int)
        self._stack, self._llvm_start = [], []

    def register(self):
        from numba.core import event

        outer = self

        class Compile(event.Listener):
            def on_start(self, ev):
                outer._stack.append((_name(ev.data["dispatcher"]), time.perf_counter()))

            def on_end(self, ev):
                name, start = outer._stack.pop()
                spent = time.perf_counter() - start
                outer.total[name] += spent
                outer.count[name] += 1
                if outer._stack:
                    outer.total[outer._stack[-1][0]] -= spent

        class Llvm(event.Listener):
            def on_start(self, ev):
                outer._llvm_start.append(time.perf_counter())

            def on_end(self, ev):
                spent = time.perf_counter() - outer._llvm_start.pop()
                if not outer._llvm_start and outer._stack:
                    outer.llvm[outer._stack[-1][0]] += spent

        event.register("numba:compile", Compile())
        event.register("numba:llvm_lock", Llvm())


def _name(dispatcher):
    """module.function, with a generated kernel's module named by its template (spinorbit.base.linker)."""
    module = dispatcher.py_func.__module__
    if module.startswith("spinorbit_"):
        module = "generated"
    return f"{module}.{dispatcher.py_func.__qualname__}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scenario", nargs="?", default="scenarios/moon_libration.toml")
    parser.add_argument("--top", type=int, default=25)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        os.environ.update(NUMBA_CACHE_DIR=f"{tmp}/numba", SPINORBIT_CACHE_DIR=f"{tmp}/spinorbit", SPINORBIT_QUIET="1")
        times = CompileTimes()
        times.register()
        from spinorbit.edge import cli

        start = time.perf_counter()
        code = cli.main(["run", str(ROOT / args.scenario), "--out", f"{tmp}/run"])
        wall = time.perf_counter() - start
    compiling, llvm = sum(times.total.values()), sum(times.llvm.values())
    print(f"{args.scenario}: run {wall:.1f} s (exit {code}), compiling {compiling:.1f} s, of it LLVM {llvm:.1f} s\n")
    print("| function | exclusive s | LLVM s | specialisations |\n|---|---|---|---|")
    for name, spent in sorted(times.total.items(), key=lambda kv: -kv[1])[:args.top]:
        print(f"| {name} | {spent:.2f} | {times.llvm[name]:.2f} | {times.count[name]} |")


if __name__ == "__main__":
    sys.exit(main())
