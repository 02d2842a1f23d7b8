"""The per-item costs behind the up-front estimate (each Scene.cost, scene.NBODY_COSTS), measured, beside
the estimate.

    python benchmarks/bench_costs.py [--only KIND ...]      # KIND "nbody": the N-body stages only

Each case runs a scene (its own settings: error estimate, plots) twice through the command line, in
fresh processes with warm kernel caches,
at two sizes of one count (integrator steps, output rows, orbit samples), and takes the slope:
seconds per integrator step from the wall time, bytes per row or sample from the peak resident
memory (VmHWM of the process image).  Printed beside each: what the scene's ``Scene.cost`` holds and the estimate it
gives for the larger run against the measured one.  The N-body stages (``nbody``) are timed in this process at
two sizes each, wall and CPU time: the deep-time orbital solution per WHFast step (2 and 10 kyr back, fresh
files), REBOUND's IAS15 run of orbit.source = 'rebound' per simulated day (integrated out 20 and 100 yr).
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from spinorbit.edge.scenarios import load_scenario  # noqa: E402 (after the checkout is put on sys.path)

CHILD = """
import json, sys, time
from spinorbit.edge.cli import main
start = time.perf_counter()
code = main(sys.argv[1:])
peak = next(int(line.split()[1]) * 1024 for line in open("/proc/self/status") if line.startswith("VmHWM"))
print(json.dumps({"code": code, "wall_s": time.perf_counter() - start, "peak_bytes": peak}))
"""
QUIET = []                     # the scenes' own settings (error estimate, plots): what a user's run costs
# (kind, count, scenario, common overrides, the two sizes as overrides)
CASES = [
    ("coupled_conservation", "integrator steps", "scenarios/stress/coupled_conservation.toml",
     ["span.end=100 d", "span.step=1 d"], ["integrator.step=0.05 d", "integrator.step=0.004 d"]),
    ("earth_moon_coupled", "integrator steps", "scenarios/earth_moon_coupled.toml",
     ['span.start="2000-01-01T12:00:00"', "span.end=400 d", "span.step=4 d"],
     ["integrator.step=0.5 d", "integrator.step=0.04 d"]),
    ("moon_libration", "integrator steps", "scenarios/moon_libration.toml",
     ['span.start="2000-01-01T12:00:00"', "span.end=4000 d", "span.step=40 d"],
     ["integrator.step=2 d", "integrator.step=0.1 d"]),
    ("stress_mercury", "integrator steps", "scenarios/stress/mercury_3_2.toml",
     ["span.end=2 yr", "span.step=1 d"],
     ["integrator.step=0.5 d", "integrator.step=0.002 d"]),
    ("moon_libration", "orbit samples", "scenarios/moon_libration.toml",
     ['span.start="2000-01-01T12:00:00"', "span.end=2000 d", "span.step=20 d"],
     ["orbit.step=0.1 d", "orbit.step=0.01 d"]),
    ("earth_precession_nutation", "orbit samples", "scenarios/earth_precession_nutation.toml",
     ['span.start="2000-01-01T12:00:00"', "span.end=2000 d", "span.step=20 d"],
     ["orbit.sample_step=0.5 d", "orbit.sample_step=0.05 d"]),
    ("p93_planar_libration", "output rows", "scenarios/p93_bounded.toml", ["span.end=2000 d"],
     ["span.step=0.1 d", "span.step=0.01 d"]),
    ("free_body", "output rows", "scenarios/free_body.toml", ["span.end=2000 d"],
     ["span.step=0.1 d", "span.step=0.01 d"]),
]


def measure(scenario, sets, out):
    argv = ["--quiet", "run", scenario, "--out", str(out), "--force"]
    for assignment in QUIET + sets:
        argv += ["--set", assignment]
    done = subprocess.run([sys.executable, "-c", CHILD, *argv], cwd=ROOT, capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": str(ROOT)}, check=False)
    if done.returncode != 0 or not done.stdout.strip():
        raise RuntimeError(f"{scenario} {sets}: {done.stderr.strip()[-500:]}")
    return json.loads(done.stdout.strip().splitlines()[-1])


def timed(call):
    """(wall s, CPU s) of ``call()``."""
    wall, cpu = time.perf_counter(), time.process_time()
    call()
    return time.perf_counter() - wall, time.process_time() - cpu


def nbody_costs():
    """Rows of the N-body stages: (count, per-item wall and CPU slopes, NBODY_COSTS, estimate vs measured)."""
    from spinorbit.orbits import nbody, solution
    from spinorbit.scene.declaration import NBODY_COSTS

    settings = solution.Settings()
    with tempfile.TemporaryDirectory() as tmp:
        cases = {"WHFast steps": [(kyr * 365250.0 / settings.step_d,
                                   lambda kyr=kyr: solution.solve(settings, -kyr * 365250.0, 0.0,
                                                                  path=Path(tmp) / f"{kyr}.npz"))
                                  for kyr in (2, 10)],
                 "IAS15 days": [(years * 365.25, lambda years=years: nbody.ReboundOrbits(
                     "earth", ("moon",), 0.0, 1.0, step=1.0, epoch=-years * 365.25)) for years in (20, 100)]}
        for what, sizes in cases.items():
            (n0, first), (n1, second) = sizes
            (w0, c0), (w1, c1) = timed(first), timed(second)
            wall, cpu = (w1 - w0) / (n1 - n0), (c1 - c0) / (n1 - n0)
            print(f"| N-body | {what} | {wall:.3g} s ({cpu:.3g} s CPU) | {NBODY_COSTS[what]:.3g} s | "
                  f"{n1 * NBODY_COSTS[what]:.3g} vs {w1:.3g} s ({n1:,.0f} {what}) |", flush=True)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--only", nargs="*", help="scene kinds to measure")
    args = parser.parse_args()
    print("| kind | count | measured | in Scene.cost | estimate vs measured, larger run |")
    print("|---|---|---|---|---|")
    if args.only and "nbody" in args.only:
        nbody_costs()
    with tempfile.TemporaryDirectory() as tmp:
        for kind, what, scenario, common, sizes in CASES:
            if args.only and kind not in args.only:
                continue
            runs, counts = [], []
            for size in sizes:
                measure(scenario, common + [size], Path(tmp) / "warm")      # compile and cache first
                runs.append(measure(scenario, common + [size], Path(tmp) / "out"))
                counts.append(load_scenario(ROOT / scenario, QUIET + common + [size]).counts()[what])
            field, unit = ("wall_s", "s") if what == "integrator steps" else ("peak_bytes", "B")
            slope = (runs[1][field] - runs[0][field]) / (counts[1] - counts[0])
            loaded = load_scenario(ROOT / scenario, QUIET + common + [sizes[1]])
            costs = loaded.cost()
            held = costs.step_s if what == "integrator steps" else costs.bytes_per[what]
            estimate = loaded.estimate()["time_s" if field == "wall_s" else "memory_bytes"]
            print(f"| {kind} | {what} | {slope:.3g} {unit} | {held:.3g} {unit} | "
                  f"{estimate:.3g} vs {runs[1][field]:.3g} {unit} ({counts[1]:,.0f} {what}) |", flush=True)
            time.sleep(0.1)


if __name__ == "__main__":
    main()
