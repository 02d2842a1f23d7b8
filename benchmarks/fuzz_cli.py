"""Fuzz the command line: mutated scenes run through `spinorbit run`, each outcome classified.

    python benchmarks/fuzz_cli.py [--cases 120] [--seed 13] [--timeout 120] [--out runs/fuzz] [--near]

Mutations of four scenes (p93_bounded, free_body, p96_earthlike, moon_libration on a short span):
wrong types, NaN/inf/huge/zero numbers, wrong units, bad dates, long strings, non-UTF-8 bytes,
deep nesting, integers past Python's digit limit, as file edits and as ``--set``; with
``--near``, numbers (plausible and extreme) in each key's own unit, which probe the ranges and
run.  Outcomes:
``error`` (exit 2, one stderr line), ``ok`` (exit 0, strict JSON summary without NaN),
``failed`` (exit 3), and the bad ones: ``traceback``, ``hang`` (timeout), ``nan`` (exit 0 with a
non-finite summary), ``noisy`` (exit 2 with more than one line), ``other``.  Writes
``<out>/fuzz_cli.csv`` and prints the counts.  Not a test: each run pays the start-up.
"""
import argparse
import csv
import json
import random
import subprocess
import sys
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SHORT = {"p93_bounded": ['span.end="20 d"'], "free_body": ['span.end="20 d"'],
         "p96_earthlike": ['span.end="5 d"'],
         "moon_libration": ['span.start="2000-01-01T12:00:00"', 'span.end="4 d"', "model.level=1"]}
KEYS = {"p93_bounded": ["orbit.gm", "orbit.radius", "orbit.rate", "body.moments", "libration.energy_over_n"],
        "free_body": ["body.moments", "body.omega0", "body.attitude0"],
        "p96_earthlike": ["body.spin", "body.obliquity", "orbit.gm", "orbit.radius", "orbit.rate"],
        "moon_libration": ["orbit.source", "orbit.step", "model.level"]}
COMMON = ["span.start", "span.end", "span.step", "integrator.rtol", "integrator.atol", "integrator.max_step",
          "integrator.method", "scene.kind", "scene.title", "output.plots"]
NUMBERS = ["0", "-1", "1", "nan", "inf", "-inf", "1e-300", "1e300", "1e999", "10", "0.5", "1e-7", "9" * 5000]
UNITS = ["", "d", "s", "yr", "km", "deg", "rad/d", "deg/d", "km3/s2", "foo"]
TEXTS = ['"2000-13-01"', '"1899-12-31"', '"9999-12-31T23:59:59"', '"x"', '"' + "y" * 20000 + '"', "{a = 1}",
         "[1, 2]", "[" * 2000 + "]" * 2000, "true", '"de421"', '"/nonexistent.bsp"', '"rebound"']


# The key's own unit, so that a value passes the unit check and probes the key's range.
UNIT_OF = {"orbit.gm": "km3/s2", "orbit.radius": "km", "orbit.rate": "deg/d", "body.spin": "rad/d",
           "body.obliquity": "deg", "span.step": "d", "span.end": "d", "orbit.step": "d", "integrator.rtol": "",
           "integrator.atol": "", "integrator.max_step": "", "libration.energy_over_n": "", "model.level": ""}
NEAR = ["0.1", "3", "0.001", "100", "1e4", "1e-4", "2e5", "-3", "0.9", "1e6"]


def mutation(rng, scene, near):
    """One (--set list, file edit or None) mutation; ``near``: a plausible number in the key's own unit."""
    key = rng.choice(KEYS[scene] + COMMON)
    if near and key in UNIT_OF:
        number = rng.choice(NEAR + NUMBERS[:9])
        return [f"{key}={number}" if not UNIT_OF[key] else f'{key}="{number} {UNIT_OF[key]}"'], None
    kind = rng.random()
    if kind < 0.45:
        value = f'"{rng.choice(NUMBERS)} {rng.choice(UNITS)}"'.replace(' "', '"')
    elif kind < 0.65:
        value = rng.choice(NUMBERS)
    elif kind < 0.9:
        value = rng.choice(TEXTS)
    else:
        return [], rng.choice([b"\xe9", b"\xff\xfe", b"\x00", b"[[[[[[[[[[", b'"'])
    return [f"{key}={value}"], None


def run_case(scene, sets, junk, out, timeout):
    path = ROOT / "scenarios" / f"{scene}.toml"
    if junk is not None:
        raw = path.read_bytes()
        at = raw.index(b'title = "') + 9
        path = out / f"{scene}_junk.toml"
        path.write_bytes(raw[:at] + junk + raw[at:])
    run_dir = out / "run"
    command = [sys.executable, "-m", "spinorbit.cli", "run", str(path), "--out", str(run_dir), "--force",
               "--set", "output.plots=false", "--set", "integrator.estimate_error=false"]
    for assignment in SHORT[scene] + sets:
        command += ["--set", assignment]
    try:
        done = subprocess.run(command, cwd=ROOT, capture_output=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return "hang", ""
    err = done.stderr.decode(errors="replace").strip()
    if "Traceback" in err:
        return "traceback", err.splitlines()[-1]
    if done.returncode == 2:
        return ("error" if len(err.splitlines()) == 1 else "noisy"), err[:300]
    if done.returncode == 3:
        return "failed", err.splitlines()[0][:300] if err else ""
    if done.returncode == 0:
        try:
            json.loads((run_dir / "summary.json").read_text(),
                       parse_constant=lambda c: (_ for _ in ()).throw(ValueError(c)))
        except ValueError as exc:
            return "nan", str(exc)
        return "ok", ""
    return "other", f"exit {done.returncode}: {err[:300]}"


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--cases", type=int, default=120)
    parser.add_argument("--seed", type=int, default=13)
    parser.add_argument("--timeout", type=float, default=120.0)
    parser.add_argument("--out", default="runs/fuzz")
    parser.add_argument("--near", action="store_true", help="plausible numbers in each key's own unit")
    args = parser.parse_args()
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    rng = random.Random(args.seed)
    rows = []
    for i in range(args.cases):
        scene = rng.choice(sorted(SHORT))
        sets, junk = mutation(rng, scene, args.near)
        outcome, detail = run_case(scene, sets, junk, out, args.timeout)
        rows.append({"case": i, "scene": scene, "set": " ".join(s[:80] for s in sets),
                     "junk": junk, "outcome": outcome, "detail": detail})
        print(f"{i:4d} {outcome:9s} {scene:15s} {rows[-1]['set'][:60]} {junk or ''} {detail[:120]}", flush=True)
    with open(out / "fuzz_cli.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    print(dict(Counter(r["outcome"] for r in rows)))


if __name__ == "__main__":
    main()
