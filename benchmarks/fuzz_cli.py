"""Fuzz the command line and the Python API: mutated inputs through `run`, `sweep`, `bench`, `list` and
``spinorbit.run_scenario``, each outcome classified.

    python benchmarks/fuzz_cli.py [--cases 200] [--seed 27] [--timeout 180] [--out runs/fuzz]
                                  [--commands run,sweep,bench,list,api,signal,damage] [--near]

Mutations: scene values (wrong types, NaN/inf/huge/zero numbers, wrong units, bad dates, long strings,
non-UTF-8 bytes, deep nesting, integers past Python's digit limit; as file edits and as ``--set``;
with ``--near``, numbers in each key's own unit, which probe the ranges and run), output directories
(a file, a FIFO, a dangling link, a folder holding foreign files, links, sockets or FIFOs, names with
glob characters, names too long, a path under a file), ``--vary`` grids, ``--methods``/``--budget``,
scheduler addresses, folders to list (FIFOs, links to devices, binary and huge files), and Python
objects of every type passed to ``run_scenario``.  Outcomes: ``error`` (exit 2, one stderr line),
``ok`` (exit 0; a run's summary is strict JSON without NaN and its files are there), ``failed``
(exit 3 with one error line, or a sweep's exit 1), and the bad ones: ``traceback``, ``hang``
(timeout), ``killed`` (a signal), ``nan`` (exit 0 with a non-finite or missing result), ``noisy``
(exit 2 with more than one line), ``other``.  Writes ``<out>/fuzz_cli.csv`` and prints the counts.

``signal``: SIGINT or SIGTERM at a random moment of a checkpointed run (free_body on rk8), a run on REBOUND's
orbits (moon_libration_rebound), a sweep, or a deep-time orbital-solution build; then the same command again
(``--resume`` for a run).  Outcomes: ``interrupted`` (exit 130, one line, and the next command finishes: a run
resumed, a solution continued bit for bit as a fresh one, a sweep's finished members kept, no staging left) or
``finished`` (the signal came after the end), and the bad ones: ``hang`` (still running 60 s after the signal),
``traceback``, ``not-continued`` (the next command failed), ``wrong`` (a continued solution differs from a
fresh one), ``lost`` (a stopped sweep left its members in a hidden staging folder).

``damage``: a file of every kind spinorbit writes, damaged (truncated, a byte flipped, emptied, garbage, a
FIFO, a link to /dev/zero, a folder) and read again: an orbital solution (``orbit.file``), a run's checkpoint
(``--resume``), a stored solution of the API, a generated kernel module, numba's index and data files of a
kernel, a run directory's manifest and summary.  Outcomes: ``error`` (exit 2, one line), ``repaired`` (exit 0,
the damage said in one line and the file rebuilt), ``ok`` (exit 0: the damage was in a part nothing reads, or
the file is rewritten whole), and the bad ones as above.

Not a test: each case pays the start-up of a process.
"""
import argparse
import csv
import json
import os
import random
import shutil
import signal
import socket
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
SHORT = {"p93_bounded": ['span.end="20 d"'], "free_body": ['span.end="20 d"'],
         "p96_earthlike": ['span.end="5 d"'],
         "moon_libration": ['span.start="2000-01-01T12:00:00"', 'span.end="4 d"', "model.level=1"],
         "stress/coupled_conservation": ['span.end="4 d"', 'span.step="1 d"']}
KEYS = {"p93_bounded": ["orbit.gm", "orbit.radius", "orbit.rate", "body.moments", "libration.energy_over_n"],
        "free_body": ["body.moments", "body.omega0", "body.attitude0"],
        "p96_earthlike": ["body.spin", "body.obliquity", "orbit.gm", "orbit.radius", "orbit.rate"],
        "moon_libration": ["orbit.source", "orbit.step", "model.level"],
        "stress/coupled_conservation": ["integrator.step", "model.figure_figure"]}
COMMON = ["span.start", "span.end", "span.step", "integrator.rtol", "integrator.atol", "integrator.max_step",
          "integrator.method", "scene.kind", "scene.title", "output.plots", "limits.time", "limits.memory"]
NUMBERS = ["0", "-1", "1", "nan", "inf", "-inf", "1e-300", "1e300", "1e999", "10", "0.5", "1e-7", "9" * 5000]
UNITS = ["", "d", "s", "yr", "km", "deg", "rad/d", "deg/d", "km3/s2", "GB", "h", "foo"]
TEXTS = ['"2000-13-01"', '"1899-12-31"', '"9999-12-31T23:59:59"', '"x"', '"' + "y" * 20000 + '"', "{a = 1}",
         "[1, 2]", "[" * 2000 + "]" * 2000, "true", '"de421"', '"/nonexistent.bsp"', '"rebound"',
         "[1, 1, 1e30]"]
UNIT_OF = {"orbit.gm": "km3/s2", "orbit.radius": "km", "orbit.rate": "deg/d", "body.spin": "rad/d",
           "body.obliquity": "deg", "span.step": "d", "span.end": "d", "orbit.step": "d",
           "integrator.rtol": "",
           "integrator.atol": "", "integrator.max_step": "", "libration.energy_over_n": "", "model.level": "",
           "integrator.step": "d", "limits.time": "s", "limits.memory": "GB"}
NEAR = ["0.1", "3", "0.001", "100", "1e4", "1e-4", "2e5", "-3", "0.9", "1e6", "4e-4"]
OUTS = ["fresh", "nested", "file", "fifo", "dangling link", "link to a folder", "foreign files", "glob [1]",
        "too long", "under a file", "socket inside", "fifo inside", "empty folder inside", "previous run"]
VARY = ['integrator.rtol=1e-8,1e-10', 'span.end="5 d","6 d"', "body.moments.0=nan,1", "x.y=1,2",
        "integrator.rtol=", "=1", "span.step=" + ",".join(["1 d"] * 40), 'integrator.method="rk8","euler"']
SCHEDULERS = ["synchronous", "synchronous", "tcp://127.0.0.1:9", "tcp://", "udp://x", "local2"]
METHODS = [None, "dop853", "rk8,rk4", "euler", "", "rk8,rk8", "strang"]
BUDGETS = ["0.5", "nan", "inf", "-1", "0", "1e9", "0.2"]
API_ARGS = ["None", "42", "3.5", "b'scenarios/free_body.toml'", "['scenarios/free_body.toml']", "{}",
            "Path('scenarios/free_body.toml')", "'scenarios/free_body.toml'", "'nope.toml'", "'scenarios'",
            "'scenarios/free_body.toml\\x00'", "object()"]
API_SETS = ["()", "None", "'span.end=5 d'", "['span.end=5 d']", "[1]", "[b'span.end=5 d']",
            "['span.end=5 d', None]",
            "('span.end=5 d', 'output.plots=false')", "{'span.end': '5 d'}", "['x' * 100000 + '=1']",
            "['span.end=nan d']", "['span.end=5 d', 'body.moments=[1, 1, 1e30]']"]


def scene_mutation(rng, scene, near):
    """One (--set list, file edit or None) mutation of a scene's values."""
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


def make_out(kind, work):
    """An --out of the given kind under ``work`` (emptied first); returns its path."""
    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    out = work / "out"
    if kind == "nested":
        out = work / "a" / "b" / "out"
    elif kind == "file":
        out.write_text("a file of the user's\n")
    elif kind == "fifo":
        os.mkfifo(out)
    elif kind == "dangling link":
        os.symlink(work / "nowhere", out)
    elif kind == "link to a folder":
        (work / "real").mkdir()
        os.symlink(work / "real", out)
    elif kind == "glob [1]":
        out = work / "out[1]"
        (work / "out1").mkdir()
        (work / "out1" / "keep.txt").write_text("keep\n")
    elif kind == "too long":
        out = work / ("x" * 300)
    elif kind == "under a file":
        (work / "file").write_text("x")
        out = work / "file" / "out"
    elif kind in ("foreign files", "socket inside", "fifo inside", "empty folder inside"):
        out.mkdir()
        if kind == "foreign files":
            (out / "notes.txt").write_text("mine\n")
        elif kind == "socket inside":
            server = socket.socket(socket.AF_UNIX)
            server.bind(str(out / "s"))
            server.close()
        elif kind == "fifo inside":
            os.mkfifo(out / "summary.json")
        else:
            (out / "empty").mkdir()
    return out


def classify(done, out, check_summary):
    err = done.stderr.decode(errors="replace").strip()
    lines = err.splitlines()
    if "Traceback" in err:
        return "traceback", lines[-1][:300]
    if done.returncode < 0:
        return "killed", f"signal {-done.returncode}"
    if done.returncode == 2:
        return ("error" if len(lines) == 1 else "noisy"), err[:300]
    if done.returncode in (1, 3):
        return "failed", lines[-1][:300] if lines else ""
    if done.returncode == 0:
        if check_summary:
            try:
                json.loads((out / "summary.json").read_text(),
                           parse_constant=lambda c: (_ for _ in ()).throw(ValueError(c)))
            except (OSError, ValueError) as exc:
                return "nan", str(exc)[:300]
        return "ok", ""
    return "other", f"exit {done.returncode}: {err[:300]}"


def execute(command, timeout):
    try:
        return subprocess.run(command, cwd=ROOT, capture_output=True, timeout=timeout, check=False,
                              env={**os.environ, "PYTHONPATH": str(ROOT), "SPINORBIT_QUIET": "1"})
    except subprocess.TimeoutExpired:
        return None


def case_run(rng, args, work):
    scene = rng.choice(sorted(SHORT))
    sets, junk = scene_mutation(rng, scene, args.near) if rng.random() < 0.8 else ([], None)
    path = ROOT / "scenarios" / f"{scene}.toml"
    if junk is not None:
        raw = path.read_bytes()
        at = raw.index(b'title = "') + 9
        path = work.parent / f"{scene.replace('/', '_')}_junk.toml"
        path.write_bytes(raw[:at] + junk + raw[at:])
    out_kind = rng.choice(OUTS) if rng.random() < 0.4 else "previous run"
    out = make_out(out_kind, work)
    flags = rng.sample(["--force", "--resume", "--strict"], rng.randint(0, 2))
    command = [sys.executable, "-m", "spinorbit.edge.cli", "run", str(path), "--out", str(out), *flags,
               "--set", "output.plots=false", "--set", "integrator.estimate_error=false"]
    for assignment in SHORT[scene] + sets:
        command += ["--set", assignment]
    done = execute(command, args.timeout)
    label = f"{scene} {' '.join(s[:60] for s in sets)} {junk or ''} out={out_kind} {' '.join(flags)}"
    if done is None:
        return label, "hang", ""
    return label, *classify(done, out, done.returncode == 0)


def case_sweep(rng, args, work):
    out_kind = rng.choice(OUTS) if rng.random() < 0.3 else "fresh"
    out = make_out(out_kind, work)
    vary = rng.sample(VARY, rng.randint(1, 2))
    scheduler = rng.choice(SCHEDULERS)
    command = [sys.executable, "-m", "spinorbit.edge.cli", "sweep", str(ROOT / "scenarios" / "free_body.toml"),
               "--scheduler", scheduler, "--out", str(out), "--set", 'span.end="5 d"',
               "--set", "output.plots=false"]
    for item in vary:
        command += ["--vary", item]
    command += ["--force"] if rng.random() < 0.3 else []
    done = execute(command, args.timeout)
    label = f"sweep {' '.join(v[:40] for v in vary)} {scheduler} out={out_kind}"
    if done is None:
        return label, "hang", ""
    outcome, detail = classify(done, out, False)
    if outcome == "ok" and not (out / "sweep.csv").is_file():
        return label, "nan", "exit 0 without sweep.csv"
    return label, outcome, detail


def case_bench(rng, args, work):
    out_kind = rng.choice(OUTS) if rng.random() < 0.3 else "fresh"
    out = make_out(out_kind, work)
    scene = rng.choice(["free_body", "p93_bounded"])
    methods, budget = rng.choice(METHODS), rng.choice(BUDGETS)
    command = [sys.executable, "-m", "spinorbit.edge.cli", "bench", str(ROOT / "scenarios" / f"{scene}.toml"),
               "--budget", budget, "--out", str(out), "--set", 'span.end="5 d"']
    command += ["--methods", methods] if methods is not None else []
    sets, _ = scene_mutation(rng, scene, args.near) if rng.random() < 0.3 else ([], None)
    for assignment in sets:
        command += ["--set", assignment]
    done = execute(command, args.timeout)
    label = f"bench {scene} methods={methods} budget={budget} out={out_kind} {' '.join(s[:40] for s in sets)}"
    if done is None:
        return label, "hang", ""
    outcome, detail = classify(done, out, False)
    if outcome == "ok" and not (out / "work_precision.csv").is_file():
        return label, "nan", "exit 0 without work_precision.csv"
    return label, outcome, detail


def case_list(rng, args, work):
    shutil.rmtree(work, ignore_errors=True)
    folder = work / "scenarios"
    folder.mkdir(parents=True)
    made = []
    for i in range(rng.randint(1, 5)):
        kind = rng.choice(["good", "fifo", "zero", "binary", "huge", "deep", "dangling", "loop", "dir.toml"])
        path = folder / f"{i}_{kind}.toml"
        if kind == "good":
            path.write_text((ROOT / "scenarios" / "free_body.toml").read_text())
        elif kind == "fifo":
            os.mkfifo(path)
        elif kind == "zero":
            os.symlink("/dev/zero", path)
        elif kind == "binary":
            path.write_bytes(bytes(rng.randrange(256) for _ in range(200)))
        elif kind == "huge":
            path.write_bytes(b"#" * (3 << 20))
        elif kind == "deep":
            path.write_text("x = " + "[" * 5000 + "]" * 5000 + "\n")
        elif kind == "dangling":
            os.symlink(folder / "nowhere.toml", path)
        elif kind == "loop":
            os.symlink(folder, folder / f"{i}_loop")
        else:
            path.mkdir()
        made.append(kind)
    target = rng.choice([folder, folder, work / "missing", folder / f"0_{made[0]}.toml"])
    done = execute([sys.executable, "-m", "spinorbit.edge.cli", "list", str(target)], args.timeout)
    label = f"list {','.join(made)} target={target.name}"
    if done is None:
        return label, "hang", ""
    return label, *classify(done, target, False)


API = """
import math, json, sys
from pathlib import Path
import spinorbit
from spinorbit.base.errors import SpinorbitError
try:
    result = spinorbit.run_scenario({scenario}, {overrides})
except SpinorbitError as exc:
    print(str(exc), file=sys.stderr)
    sys.exit(2 if "\\n" not in str(exc) else 5)
bad = [k for k, v in result.summary.get("comparison", {{}}).items()
       if isinstance(v, float) and not math.isfinite(v)]
json.dumps(result.summary, allow_nan=False)
sys.exit(6 if bad else 0)
"""


def case_api(rng, args, work):
    scenario, overrides = rng.choice(API_ARGS), rng.choice(API_SETS)
    if scenario == "'scenarios/free_body.toml'" and overrides in ("()", "None"):
        overrides = "['span.end=5 d']"
    done = execute([sys.executable, "-c", API.format(scenario=scenario, overrides=overrides)], args.timeout)
    label = f"run_scenario({scenario[:40]}, {overrides[:40]})"
    if done is None:
        return label, "hang", ""
    if done.returncode == 6:
        return label, "nan", "non-finite comparison"
    return label, *classify(done, work, False)


CLI = [sys.executable, "-m", "spinorbit.edge.cli", "--quiet"]
DEEP = ["earth_deep_time", "--set", 'span.end="-10 kyr"', "--set", 'span.step="1 kyr"', "--set",
        'integrator.step="100 yr"', "--set", "output.plots=false"]
TARGETS = {
    "run": lambda w: [*CLI, "run", "scenarios/free_body.toml", "--out", str(w / "out"), "--set", "span.end=4000 d",
                      "--set", "integrator.method=rk8", "--set", "integrator.step=0.002 d", "--set",
                      "output.plots=false"],
    "rebound run": lambda w: [*CLI, "run", "moon_libration_rebound", "--out", str(w / "out"), "--set",
                              'span.start="1969-06-28T12:00:00"', "--set", "span.end=60 d", "--set",
                              "output.plots=false"],
    "sweep": lambda w: [*CLI, "sweep", "scenarios/free_body.toml", "--vary", "integrator.rtol=1e-8,1e-9,1e-10,1e-11",
                        "--set", "span.end=1000 d", "--set", "output.plots=false", "--scheduler", "synchronous",
                        "--out", str(w / "out")],
    "solution build": lambda w: [*CLI, "run", *DEEP, "--set", f"orbit.file={w / 'solution.npz'}", "--out",
                                 str(w / "out")],
}
DAMAGES = ["truncated", "byte flipped", "emptied", "garbage", "fifo", "link to /dev/zero", "folder"]


def damage(path, how, rng):
    """Damage the file at ``path`` as ``how`` says."""
    data = path.read_bytes() if path.is_file() else b""
    path.unlink()
    if how == "truncated":
        path.write_bytes(data[:rng.randrange(max(len(data), 1))])
    elif how == "byte flipped":
        at = rng.randrange(max(len(data), 1))
        path.write_bytes(data[:at] + bytes([data[at] ^ (1 << rng.randrange(8))]) + data[at + 1:] if data else b"x")
    elif how == "emptied":
        path.write_bytes(b"")
    elif how == "garbage":
        path.write_bytes(bytes(rng.randrange(256) for _ in range(max(len(data) // 10, 64))))
    elif how == "fifo":
        os.mkfifo(path)
    elif how == "link to /dev/zero":
        os.symlink("/dev/zero", path)
    else:
        path.mkdir()


def answer_ctrl_c():
    """In the child: SIGINT at its default, as in a terminal (a job started in the background ignores it, and
    Python then never installs its handler)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def outcome_of(done, err, ok_words=("damaged", "refused", "rebuilt", "compiled again", "computing it again")):
    """The outcome of a finished command (None: it did not finish)."""
    if done is None:
        return "hang"
    lines = err.strip().splitlines()
    if "Traceback" in err:
        return "traceback"
    if done.returncode == 130:
        return "interrupted" if lines and lines[-1] == "interrupted" else "noisy"
    if done.returncode == 2:          # one error line, last (lines before it: notices of a --set's effect)
        return "error" if [line.startswith("error:") for line in lines].count(True) == 1 and \
            lines[-1].startswith("error:") else "noisy"
    if done.returncode == 0:
        return "repaired" if any(w in err for w in ok_words) else "ok"
    return "killed" if done.returncode < 0 else f"exit {done.returncode}"


def fresh_solution(base):
    """The orbital solution DEEP computes, once, uninterrupted (the reference a continued one must equal)."""
    import numpy as np

    path = base / "reference_solution.npz"
    if not path.exists():
        execute([*CLI, "run", *DEEP, "--set", f"orbit.file={path}", "--out", str(base / "reference_out")], 900)
    with np.load(path) as data:
        return data["eccentricity_vector"]


def case_signal(rng, args, work):
    import numpy as np

    shutil.rmtree(work, ignore_errors=True)
    work.mkdir(parents=True)
    target = rng.choice(sorted(TARGETS))
    sig = rng.choice([signal.SIGINT, signal.SIGTERM])
    delay = rng.uniform(0.3, 8.0)
    command = TARGETS[target](work)
    process = subprocess.Popen(command, cwd=ROOT, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=ENV,
                               preexec_fn=answer_ctrl_c)
    time.sleep(delay)
    process.send_signal(sig)
    label = f"{target} {signal.Signals(sig).name} at {delay:.1f} s"
    try:
        _, err = process.communicate(timeout=60)
    except subprocess.TimeoutExpired:
        process.kill()
        process.communicate()
        return label, "hang", ""
    err = err.decode(errors="replace")
    first = outcome_of(process, err)
    if first not in ("interrupted", "ok"):
        return label, first, err.strip()[-300:]
    if target == "sweep" and list(work.glob(".out.new-*")):
        return label, "lost", "a staging folder left"
    again = execute(command + (["--resume"] if target in ("run", "rebound run") else []), args.timeout)
    second = outcome_of(again, again.stderr.decode(errors="replace") if again else "")
    if second not in ("ok", "repaired"):
        return label, "not-continued", (again.stderr.decode(errors="replace")[-300:] if again else "")
    if target == "solution build":
        with np.load(work / "solution.npz") as data:
            if not np.array_equal(data["eccentricity_vector"], fresh_solution(work.parent)):
                return label, "wrong", "a continued solution differs from a fresh one"
    return label, "interrupted" if first == "interrupted" else "finished", err.strip().splitlines()[-1][:200] \
        if err.strip() else ""


def made_files(base):
    """{kind: (a good file of that kind, the command that reads it)}, made once under ``base``."""
    made = base / "made"
    if not made.exists():
        made.mkdir(parents=True)
        cache = made / "cache"
        env = {**ENV, "SPINORBIT_CACHE_DIR": str(cache)}
        for command in ([*CLI, "run", *DEEP, "--set", f"orbit.file={made / 'solution.npz'}", "--out",
                         str(made / "deep")],
                        [*CLI, "run", "scenarios/free_body.toml", "--out", str(made / "run"), "--set",
                         "span.end=100 d", "--set", "output.plots=false"],
                        [sys.executable, "-c", "import spinorbit; from astropy.time import Time; "
                                               "spinorbit.moon_librations(Time('2000-01-05', scale='tdb'))"]):
            subprocess.run(command, cwd=ROOT, env=env, capture_output=True, check=False)
        process = subprocess.Popen(TARGETS["run"](made), cwd=ROOT, env=env, stderr=subprocess.PIPE,
                                   preexec_fn=answer_ctrl_c)
        time.sleep(3)                          # within the run (about 7 s): its checkpoint is kept
        process.send_signal(signal.SIGINT)
        process.communicate()
    return made


def case_damage(rng, args, work):
    base = made_files(work.parent)
    shutil.rmtree(work, ignore_errors=True)
    shutil.copytree(base, work, symlinks=True)
    cache = work / "cache"
    env = {**ENV, "SPINORBIT_CACHE_DIR": str(cache)}
    kernels = sorted((cache / "kernels").glob("spinorbit_*.py"))
    numba = sorted((cache / "kernels" / "numba").glob("*.nb*"))
    kinds = {"orbital solution": (work / "solution.npz", [*CLI, "run", *DEEP, "--set",
                                                          f"orbit.file={work / 'solution.npz'}", "--out",
                                                          str(work / "deep")]),
             "checkpoint": (work / "out.checkpoint.npz", TARGETS["run"](work) + ["--resume"]),
             "stored solution": (next(iter(sorted((cache / "solutions").glob("*.npz"))), None),
                                 [sys.executable, "-c", "import spinorbit; from astropy.time import Time; "
                                                        "spinorbit.moon_librations(Time('2000-01-05', scale='tdb'))"]),
             "kernel module": (rng.choice(kernels) if kernels else None,
                               [*CLI, "run", "scenarios/free_body.toml", "--out", str(work / "run"), "--set",
                                "span.end=100 d", "--set", "output.plots=false"]),
             "numba file": (rng.choice(numba) if numba else None,
                            [*CLI, "run", "scenarios/free_body.toml", "--out", str(work / "run"), "--set",
                             "span.end=100 d", "--set", "output.plots=false"]),
             "manifest": (work / "run" / ".spinorbit-manifest.json",
                          [*CLI, "run", "scenarios/free_body.toml", "--out", str(work / "run"), "--set",
                           "span.end=100 d", "--set", "output.plots=false"]),
             "summary": (work / "run" / "summary.json",
                         [*CLI, "run", "scenarios/free_body.toml", "--out", str(work / "run"), "--set",
                          "span.end=100 d", "--set", "output.plots=false"])}
    kind = rng.choice(sorted(kinds))
    path, command = kinds[kind]
    how = rng.choice(DAMAGES)
    label = f"{kind} {how} {path.name if path else '(none made)'}"
    if path is None or not os.path.lexists(path):
        return label, "skipped", "no file of this kind was made"
    damage(path, how, rng)
    try:
        done = subprocess.run(command, cwd=ROOT, env=env, capture_output=True, timeout=args.timeout, check=False)
    except subprocess.TimeoutExpired:
        return label, "hang", ""
    err = done.stderr.decode(errors="replace")
    return label, outcome_of(done, err), err.strip()[-300:]


ENV = {**os.environ, "PYTHONPATH": str(ROOT), "SPINORBIT_QUIET": "1"}
CASES = {"run": case_run, "sweep": case_sweep, "bench": case_bench, "list": case_list, "api": case_api,
         "signal": case_signal, "damage": case_damage}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--cases", type=int, default=200)
    parser.add_argument("--seed", type=int, default=27)
    parser.add_argument("--timeout", type=float, default=180.0)
    parser.add_argument("--out", default="runs/fuzz")
    parser.add_argument("--commands", default="run,sweep,bench,list,api")
    parser.add_argument("--near", action="store_true", help="plausible numbers in each key's own unit")
    args = parser.parse_args()
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    rng = random.Random(args.seed)
    commands = args.commands.split(",")
    rows, start = [], time.monotonic()
    for i in range(args.cases):
        command = commands[i % len(commands)]
        label, outcome, detail = CASES[command](rng, args, out / "work")
        rows.append({"case": i, "command": command, "input": label[:300], "outcome": outcome,
                     "detail": detail})
        print(f"{i:4d} {outcome:9s} {label[:90]} {detail[:120]}", flush=True)
    with open(out / "fuzz_cli.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    counts = Counter((r["command"], r["outcome"]) for r in rows)
    print(f"{len(rows)} cases in {time.monotonic() - start:.0f} s:",
          {f"{c}/{o}": n for (c, o), n in sorted(counts.items())})


if __name__ == "__main__":
    main()
