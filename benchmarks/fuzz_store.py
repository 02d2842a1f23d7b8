"""A hostile trial of the solution store (spinorbit.solutions.store on spinorbit.base.verified): signals at random
moments of extensions and runs, damaged and foreign files of every kind the store writes or reads, a disk that
refuses the write, and concurrent processes, each case in fresh processes on a store of its own.

    python benchmarks/fuzz_store.py [--cases 40] [--seed 42] [--out runs/fuzz_store]
                                    [--kinds signal,run-signal,damage,folder,full-disk,concurrent]

The reference: the Moon over [-20, 60] d from J2000 computed at once in a store of its own; every answer is its
attitude (``moon.q``) at 41 dates, compared with the reference's within REFERENCE_UAS (extending in pieces differs
from one whole run by the integration's own error, ~1e-8").

- ``signal``: an extension ([-20, 60] d in one or two random pieces) sent SIGINT, SIGTERM or SIGKILL at a random
  moment within 3 s; then the whole span asked again.  ``interrupted`` / ``finished`` when the second answer
  equals the reference, the store's file is intact and no temporary file of a dead process is left.
- ``run-signal``: `spinorbit run moon_libration` (J2000, 12 d) signalled alike, then run again: its run directory
  complete or absent (never a part), the second run exit 0 and stored.
- ``damage``: the stored file, its lock or the code-version record truncated, a byte flipped, emptied, garbage,
  a FIFO, a link to /dev/zero, a folder, a link to another solution, or the stored file replaced by a solution of
  another record (planted with its hash recomputed); then ``spinorbit.moon_librations`` at 41 dates.
  ``repaired`` (the damage said in one line, the answer the reference's), ``ok`` (nothing said: the damage in a
  part nothing reads, or rewritten whole), ``error`` (one line, exit 2).
- ``folder``: the store's folder made writable by others, or another user's: ``error`` in one line, nothing
  served.
- ``full-disk``: the file-size limit (RLIMIT_FSIZE) below the file's size, once the case's kernel cache is
  written (a first call without the limit, its store then removed): the answer with one warning that it was not
  stored, no partial file left.
- ``concurrent``: three processes extending one solution over random spans and a `spinorbit cache clear` at
  once: every answer the reference's, the store whole after.

The bad outcomes: ``traceback``, ``hang`` (60 s), ``wrong`` (an answer off the reference), ``noisy`` (more than
one line said), ``partial`` (a run directory or temporary file left half-written), ``served`` (a refused folder
or file answered from), ``lost`` (a finished run not written).  Writes ``<out>/fuzz_store.csv``, prints counts.
Not a test: each case pays the start-up of processes.
"""
import argparse
import csv
import json
import os
import random
import resource
import shutil
import signal
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
T = np.linspace(-19.5, 59.5, 41)
REFERENCE_UAS = 1.0
WORKER = """
import sys, json, numpy as np, warnings
from spinorbit import solutions
from spinorbit.edge.scenarios import load_scenario
lo, hi = float(sys.argv[1]), float(sys.argv[2])
s = solutions.for_scenario(load_scenario("moon_libration"), lo, hi)
q = s.part("moon.q", np.linspace(-19.5, 59.5, 41)) if s.covers(-19.5, 59.5) else np.zeros((0, 4))
print(json.dumps(q.tolist()))            # on stdout: a file-size limit meets spinorbit's writes, not this answer's
"""
API = """
import sys, numpy as np
from astropy.time import Time
import spinorbit
from spinorbit.edge.scenarios import load_scenario
from spinorbit.solutions import for_scenario
t = Time(2451545.0 + np.linspace(-19.5, 59.5, 41), format="jd", scale="tdb")
spinorbit.moon_librations(t)
s = for_scenario(load_scenario("moon_libration"), -19.5, 59.5)
np.save(sys.argv[1], s.part("moon.q", np.linspace(-19.5, 59.5, 41)))
"""


def environment(cache):
    env = dict(os.environ, SPINORBIT_CACHE_DIR=str(cache), PYTHONPATH=str(ROOT), OPENBLAS_NUM_THREADS="1",
               PYTHONWARNINGS="default")
    return env


def fresh_cache(base):
    shutil.rmtree(base, ignore_errors=True)
    base.mkdir(parents=True, mode=0o700)
    return base


def run(args, env, timeout=120, limit=None, **kwargs):
    """(exit, stdout, stderr) of a process, "hang" as exit when it outlives ``timeout``."""
    preexec = (lambda: resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))) if limit is not None else None
    try:
        done = subprocess.run(args, env=env, capture_output=True, text=True, timeout=timeout, preexec_fn=preexec,
                              **kwargs)
    except subprocess.TimeoutExpired:
        return "hang", "", ""
    return done.returncode, done.stdout, done.stderr


def angle_uas(a, b):
    """The largest angle between two series of unit quaternions (spinorbit.base.rotations.quat_angle), in uas."""
    from spinorbit.base.rotations import quat_angle

    return float(np.max(quat_angle(a, b)) * 180 / np.pi * 3600e6)


def said(stderr):
    """The lines a process said, numba's and Python's warning source lines aside."""
    return [line for line in stderr.splitlines() if line.strip() and not line.startswith("  ")
            and "compiling" not in line]


def store_files(cache):
    folder = cache / "solutions"
    return sorted(folder.glob("*.npz")) if folder.is_dir() else []


def leftovers(cache):
    folder = cache / "solutions"
    return [p for p in folder.glob(".*tmp-*")] if folder.is_dir() else []


def intact(cache):
    """Whether every stored file reads back whole (spinorbit.base.verified.read)."""
    code = ("import sys; from pathlib import Path; from spinorbit.base import verified\n"
            "[verified.read(Path(p)) for p in sys.argv[1:]]")
    files = [str(p) for p in store_files(cache)]
    return not files or run([sys.executable, "-c", code, *files], environment(cache))[0] == 0


def answer(cache, lo, hi, tag, limit=None):
    code, out, err = run([sys.executable, "-c", WORKER, str(lo), str(hi), "-"], environment(cache), limit=limit)
    q = np.array(json.loads(out.splitlines()[-1])) if code == 0 and out.strip() else None
    return code, err, (q if q is not None and q.size else None)


def judge(code, err, q, reference):
    if code == "hang":
        return "hang"
    if "Traceback" in err:
        return "traceback"
    if code != 0:
        return "error" if len(said(err)) == 1 else "noisy"
    if q is None or angle_uas(q, reference) > REFERENCE_UAS:
        return "wrong"
    return None


def case_signal(rng, cache, reference):
    pieces = [(-20.0, 60.0)] if rng.random() < 0.5 else [(0.0, float(rng.choice([8, 20, 40]))), (-20.0, 60.0)]
    delay, sig = rng.uniform(0.0, 3.0), rng.choice([signal.SIGINT, signal.SIGTERM, signal.SIGKILL])
    for k, (lo, hi) in enumerate(pieces[:-1]):
        answer(cache, lo, hi, f"piece{k}")
    lo, hi = pieces[-1]
    proc = subprocess.Popen([sys.executable, "-c", WORKER, str(lo), str(hi), "-"],
                            env=environment(cache), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    time.sleep(delay)
    finished = proc.poll() is not None
    proc.send_signal(sig)
    try:
        _, err1 = proc.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        proc.kill()
        return "hang", f"{sig.name} at {delay:.2f}s"
    code, err, q = answer(cache, -20.0, 60.0, "after")
    bad = judge(code, err, q, reference) or ("traceback" if "Traceback" in err1 and sig != signal.SIGINT else None)
    if bad is None and not intact(cache):
        bad = "partial"
    if bad is None and leftovers(cache):
        bad = "partial"
    return bad or ("finished" if finished else "interrupted"), f"{sig.name} at {delay:.2f}s, pieces {pieces}"


def case_run_signal(rng, cache, reference):
    out = cache.parent / "run"
    args = [sys.executable, "-m", "spinorbit", "run", "moon_libration", "--set", "span.start=2000-01-01T12:00:00",
            "--set", "span.end=12 d", "--set", "span.step=0.5 d", "--set", "output.plots=false", "--out", str(out),
            "--force"]
    delay, sig = rng.uniform(0.0, 6.0), rng.choice([signal.SIGINT, signal.SIGTERM, signal.SIGKILL])
    proc = subprocess.Popen(args, env=environment(cache), stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            cwd=cache.parent)
    time.sleep(delay)
    finished = proc.poll() is not None
    proc.send_signal(sig)
    try:
        proc.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        proc.kill()
        return "hang", f"{sig.name} at {delay:.2f}s"
    written = (out / "summary.json").exists()
    if out.exists() and written != all((out / name).exists() for name in ("timeseries.ecsv", "report.md")):
        return "partial", f"{sig.name} at {delay:.2f}s: {sorted(p.name for p in out.iterdir())}"
    if finished and not written:
        return "lost", f"{sig.name} at {delay:.2f}s"
    code, _, err = run(args, environment(cache), cwd=cache.parent)
    if code != 0 or "Traceback" in err:
        return ("traceback" if "Traceback" in err else "error"), f"second run exit {code}: {said(err)[-1:]}"
    summary = json.loads((out / "summary.json").read_text())
    if not summary["solution"].get("stored") or not intact(cache):
        return "lost", f"second run not stored: {summary['solution'].get('not_stored_because')}"
    return ("finished" if finished else "interrupted"), f"{sig.name} at {delay:.2f}s"


DAMAGES = ("truncated", "flipped", "emptied", "garbage", "fifo", "dev-zero", "folder", "other-solution",
           "planted")


def damage(path, how, rng, cache):
    if how in ("fifo", "dev-zero", "folder", "other-solution") or not path.exists():
        if path.is_dir() and not path.is_symlink():
            shutil.rmtree(path)
        elif os.path.lexists(path):
            path.unlink()
    if how == "truncated":
        path.write_bytes(path.read_bytes()[: max(1, path.stat().st_size // 2)])
    elif how == "flipped":
        data = bytearray(path.read_bytes()) or bytearray(b"\0")
        spot = rng.randrange(len(data))
        data[spot] ^= 1 << rng.randrange(8)
        path.write_bytes(bytes(data))
    elif how == "emptied":
        path.write_bytes(b"")
    elif how == "garbage":
        path.write_bytes(bytes(rng.randrange(256) for _ in range(4096)))
    elif how == "fifo":
        os.mkfifo(path)
    elif how == "dev-zero":
        os.symlink("/dev/zero", path)
    elif how == "folder":
        path.mkdir()
        (path / "inside").write_text("x")
    elif how == "other-solution":            # a link to a solution of another record
        other = cache.parent / "other.npz"
        if other.exists():
            os.symlink(other, path)
        else:
            path.write_bytes(b"")
    elif how == "planted":                   # another record's arrays, the hash recomputed with the room's own
        code = ("import sys, numpy as np; from spinorbit.base import verified; e = verified.read(sys.argv[1]);"
                "e.arrays['coefficients'] = e.arrays['coefficients'] * (1 + 1e-7);"
                "e.record['keys']['model.level'] = 2; verified.write(sys.argv[1], e.arrays, e.record, e.meta)")
        run([sys.executable, "-c", code, str(path)], environment(cache))


def case_damage(rng, cache, reference):
    answer(cache, -20.0, 60.0, "first")
    other = cache.parent / "other.npz"
    if not other.exists():
        code = ("import sys, shutil; from spinorbit import solutions;"
                "from spinorbit.edge.scenarios import load_scenario;"
                "s = solutions.for_scenario(load_scenario('moon_libration', ['model.level=2']), 0.0, 4.0);"
                "shutil.copy(s.path, sys.argv[1])")
        run([sys.executable, "-c", code, str(other)], environment(cache))
    stored = store_files(cache)
    stored = [p for p in stored if "moon_libration" in p.name][:1]
    if not stored:
        return "lost", "nothing stored to damage"
    targets = {"solution": stored[0], "lock": Path(str(stored[0]) + ".lock"),
               "code record": next((cache / "solutions").glob("code-*.json"), cache / "solutions" / "code-x.json")}
    what = rng.choice(sorted(targets))
    how = rng.choice(DAMAGES if what == "solution" else DAMAGES[:7])
    damage(targets[what], how, rng, cache)
    out = cache.parent / "api.npy"
    code, _, err = run([sys.executable, "-c", API, str(out)], environment(cache), timeout=120)
    lines = [line for line in said(err) if "spinorbit:" in line or "error" in line.lower()]
    if code == "hang" or "Traceback" in err:
        return ("hang" if code == "hang" else "traceback"), f"{what} {how}: {said(err)[-1:]}"
    if code != 0:
        return ("error" if len(said(err)) == 1 else "noisy"), f"{what} {how}: {said(err)[-1:]}"
    if angle_uas(np.load(out), reference) > REFERENCE_UAS:
        return ("served" if how == "planted" else "wrong"), f"{what} {how}"
    if len(lines) > 1:
        return "noisy", f"{what} {how}: {lines}"
    return ("repaired" if lines else "ok"), f"{what} {how}: {lines[0][:100] if lines else ''}"


def case_folder(rng, cache, reference):
    answer(cache, 0.0, 8.0, "first")
    folder, how = cache / "solutions", rng.choice(["world-writable", "another user's"])
    if how == "world-writable":
        folder.chmod(0o777)
    else:
        os.chown(folder, 65534, 65534)
    out = cache.parent / "api.npy"
    code, _, err = run([sys.executable, "-c", API, str(out)], environment(cache))
    folder.chmod(0o700)
    os.chown(folder, os.getuid(), os.getgid())
    if "Traceback" in err:
        first = [line for line in err.splitlines() if "Error" in line][-1:]
        return ("error" if any("InputError" in line and "private directory" in line for line in first)
                else "traceback"), f"{how}: {first}"
    if code == 0:
        return "served", how
    return ("error" if len(said(err)) == 1 else "noisy"), f"{how}: {said(err)[-1:]}"


def case_full_disk(rng, cache, reference):
    answer(cache, 0.0, 4.0, "warm")             # the kernel cache written first: the limit meets the store's write
    shutil.rmtree(cache / "solutions")
    limit = rng.choice([0, 1000, 20_000])
    code, err, q = answer(cache, -20.0, 60.0, "full", limit=limit)
    bad = judge(code, err, q, reference)
    if bad:
        return bad, f"limit {limit} B: {said(err)[-1:]}"
    warned = [line for line in said(err) if "not stored" in line]
    left = [p for p in (cache / "solutions").iterdir() if ".tmp-" in p.name or p.suffix == ".npz"]
    if left:
        return "partial", f"limit {limit} B: {[p.name for p in left]}"
    return ("ok" if len(warned) == 1 else "noisy"), f"limit {limit} B: {warned[:1]}"


def case_concurrent(rng, cache, reference):
    spans = [(-20.0, 60.0)] + [(float(rng.choice([-20, -8, 0])), float(rng.choice([8, 24, 60]))) for _ in range(2)]
    procs = [subprocess.Popen([sys.executable, "-c", WORKER, str(lo), str(hi), "-"], env=environment(cache),
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True) for lo, hi in spans]
    time.sleep(rng.uniform(0.0, 2.0))
    clear = run([sys.executable, "-m", "spinorbit", "cache", "clear"], environment(cache))
    errors, answers = [], []
    for proc in procs:
        try:
            out, err = proc.communicate(timeout=180)
        except subprocess.TimeoutExpired:
            proc.kill()
            return "hang", f"spans {spans}"
        if proc.returncode != 0 or "Traceback" in err:
            errors.append(said(err)[-1:])
        answers.append(out)
    if errors or clear[0] != 0:
        return "traceback", f"spans {spans}: {errors} clear {clear[0]}"
    q = np.array(json.loads(answers[0].splitlines()[-1]))
    if angle_uas(q, reference) > REFERENCE_UAS:
        return "wrong", f"spans {spans}"
    if not intact(cache):
        return "partial", f"spans {spans}"
    return "ok", f"spans {spans}; clear: {clear[1].strip().splitlines()[-1][:80]}"


CASES = {"signal": case_signal, "run-signal": case_run_signal, "damage": case_damage, "folder": case_folder,
         "full-disk": case_full_disk, "concurrent": case_concurrent}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cases", type=int, default=40)
    parser.add_argument("--seed", type=int, default=42)
    parser.add_argument("--out", default="runs/fuzz_store")
    parser.add_argument("--kinds", default=",".join(CASES))
    args = parser.parse_args()
    rng, out = random.Random(args.seed), Path(args.out).absolute()
    out.mkdir(parents=True, exist_ok=True)
    reference_cache = fresh_cache(out / "reference" / "cache")
    code, err, reference = answer(reference_cache, -20.0, 60.0, "reference")
    if reference is None:
        sys.exit(f"the reference failed: {err[-500:]}")
    kinds, rows, started = args.kinds.split(","), [], time.perf_counter()
    for number in range(args.cases):
        kind = kinds[number % len(kinds)]
        base = out / f"case{number}"
        shutil.rmtree(base, ignore_errors=True)
        cache = fresh_cache(base / "cache")
        began = time.perf_counter()
        try:
            outcome, detail = CASES[kind](rng, cache, reference)
        except Exception as exc:             # the harness's own failure, kept apart from spinorbit's outcomes
            outcome, detail = "harness", f"{type(exc).__name__}: {exc}"
        rows.append({"case": number, "kind": kind, "outcome": outcome, "detail": detail,
                     "wall_s": round(time.perf_counter() - began, 1)})
        print(f"{number:3d} {kind:11s} {outcome:11s} {detail}", flush=True)
        shutil.rmtree(base, ignore_errors=True)
    with open(out / "fuzz_store.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    counts = Counter((row["kind"], row["outcome"]) for row in rows)
    print(f"{len(rows)} cases in {time.perf_counter() - started:.0f} s")
    for (kind, outcome), n in sorted(counts.items()):
        print(f"  {kind:11s} {outcome:11s} {n}")


if __name__ == "__main__":
    main()
