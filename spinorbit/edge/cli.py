"""Command line: ``spinorbit run | list | bench``.

``run`` prints the verdict first: ``<scene>: pass | fail | not-compared — <figure> <= <tolerance>
... vs <reference> (<span>)`` (spinorbit.scene.verdict), then the comparison metrics.

Exit codes: 0 the run finished (whatever its verdict); 2 bad input (one line
``error: <key>: got ...; expected ...``, or ``error: <path>: <reason>`` for a file that cannot be read or
written); 3 the integration failed (what it has is
written); 4 with ``run --strict``, the run finished but its verdict is ``fail``;
1 ``sweep`` with failed runs; 130 interrupted (Ctrl-C or SIGTERM; a checkpointed run can continue
with ``run --resume``).
"""
import argparse
import contextlib
import gc
import os
import signal
import sys
import threading
from pathlib import Path

from ..base.errors import IntegrationError, SpinorbitError
from ..base.version import __version__

EXIT_VERDICT_FAIL = 4
FORCE_HELP = ("write into an --out holding entries spinorbit did not write: they are kept, except files of "
              "the names the run writes, which it overwrites")
MAX_LISTED_BYTES = 1 << 20          # `list` reads at most this much of a file (a scenario is a few kB)
_COMMAND = False                     # this process is the spinorbit command (console), not a caller of main


def main(argv=None):
    parser = argparse.ArgumentParser(prog="spinorbit",
                                     description="Couple orbit and spin (Euler, Theoria motus ch. 16).")
    parser.add_argument("--quiet", action="store_true", help="no progress bars on stderr")
    parser.add_argument("--version", action="version", version=f"spinorbit {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    run = sub.add_parser("run", help="run a scenario and write a run directory")
    run.add_argument("scenario", help="a scenario .toml file, or a built-in scene's name (spinorbit list)")
    run.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                     help="override a scenario key by dotted path (repeatable)")
    run.add_argument("--out", help="run directory (default runs/<scenario name>)")
    run.add_argument("--strict", action="store_true",
                     help=f"exit {EXIT_VERDICT_FAIL} when the verdict is 'fail'")
    run.add_argument("--force", action="store_true", help=FORCE_HELP)
    run.add_argument("--resume", action="store_true",
                     help="continue an interrupted run from <out>.checkpoint.npz (long fixed-step scenes)")
    sweep = sub.add_parser("sweep", help="a parameter sweep / ensemble on Dask (a local cluster by default)")
    sweep.add_argument("scenario")
    sweep.add_argument("--vary", action="append", required=True, metavar="KEY=V1,V2,...",
                       help="values of one key (repeatable; the sweep is their Cartesian product)")
    sweep.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE")
    sweep.add_argument("--scheduler", default="local",
                       help="'local' (default), 'synchronous' or tcp://host:port")
    sweep.add_argument("--out", help="sweep directory (default runs/<scenario name>-sweep)")
    sweep.add_argument("--force", action="store_true", help=FORCE_HELP)
    bench = sub.add_parser("bench", help="work-precision of every suitable integrator on a scene")
    bench.add_argument("scenario")
    bench.add_argument("--methods",
                       help="comma-separated method names (default: every method that supports the scene)")
    bench.add_argument("--budget", type=float, default=10.0,
                       help="stop a method's ladder after a run this long, s")
    bench.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE")
    bench.add_argument("--out", help="output directory (default runs/<scenario name>-bench)")
    bench.add_argument("--force", action="store_true", help=FORCE_HELP)
    listing = sub.add_parser("list", help="list the built-in scenes, or the scenarios in a folder")
    listing.add_argument("folder", nargs="?", help="a folder of scenario files (default: the built-in scenes)")
    show = sub.add_parser("show", help="every key a scene reads: its value, default, unit, range and meaning")
    show.add_argument("scenario", help="a scenario .toml file, or a built-in scene's name")
    cache = sub.add_parser("cache", help="spinorbit's caches (compiled kernels, heyoka's, orbital solutions): "
                                        "where and how big; 'clear' empties them")
    cache.add_argument("action", nargs="?", choices=["show", "clear"], default="show")
    export = sub.add_parser("export", help="a scene's solution over its span as SPICE kernels (binary PCK + frame "
                                           "kernel of each attitude, SPK of the integrated positions)",
                            description="Write a scene's solution over its span as SPICE kernels.",
                            add_help=False)
    export.add_argument("-h", "--help", action=_ExportHelp, nargs=0, help="show this help and the kinds that "
                                                                          "can be exported, then exit")
    export.add_argument("scenario", help="a scenario .toml file, or a built-in scene's name")
    export.add_argument("--set", dest="overrides", action="append", default=[], metavar="KEY=VALUE",
                        help="set a key, e.g. --set span.end=2100-01-01 (repeatable; spinorbit show SCENE lists "
                             "the keys)")
    export.add_argument("--out", required=True, help="directory the kernels are written into")
    at = sub.add_parser("at", help="a body's orientation at dates, from the stored solutions (as "
                                   "spinorbit.orientation answers: moon_librations, earth_pole)",
                        description="A body's orientation at dates, from the stored solutions.", add_help=False)
    at.add_argument("-h", "--help", action=_AtHelp, nargs=0, help="show this help and the bodies, then exit")
    at.add_argument("body", help="a body a scene answers for (--help lists them: e.g. moon, earth, mars)")
    at.add_argument("dates", nargs="+", metavar="DATE", help="ISO dates or times, e.g. 2027-03-01 "
                                                             "2027-03-01T12:00:00")
    at.add_argument("--scale", default="utc", choices=["utc", "tt", "tdb"], help="the dates' time scale "
                                                                                  "(default utc)")
    at.add_argument("--format", default="csv", choices=["csv", "ecsv"],
                    help="csv: a header line with each column's unit; ecsv: astropy's, with units and meta")
    args, extra = parser.parse_known_args(argv)
    if extra:
        parser.error(f"unrecognized arguments: {' '.join(extra)}{_quote_hint(argv, extra)}")
    if args.quiet:
        os.environ["SPINORBIT_QUIET"] = "1"          # read by spinorbit.base.progress, here and in Dask workers
    try:
        if args.command == "run":
            with _sigterm_interrupts():
                return _run(args)
        if args.command == "sweep":
            with _sigterm_interrupts():
                return _sweep(args)
        if args.command == "bench":
            with _sigterm_interrupts():
                return _bench(args)
        if args.command == "cache":
            return _cache(args.action)
        if args.command == "show":
            return _show(args.scenario)
        if args.command == "export":
            return _export(args)
        if args.command == "at":
            return _at(args)
        return _list(args.folder)
    except IntegrationError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 3
    except KeyboardInterrupt:
        if _COMMAND:
            signal.signal(signal.SIGINT, signal.SIG_IGN)     # stopping: see _stopping
        print("interrupted", file=sys.stderr)
        return 130
    except SpinorbitError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except OSError as exc:                     # a file the command could not read or write: one line
        where = f"{_printable(exc.filename)}: " if exc.filename else ""
        print(f"error: {where}{exc.strerror or exc}", file=sys.stderr)
        return 2


def _quote_hint(argv, extra):
    """A hint when a word left over follows a --set or --vary: its value held a space and was not quoted."""
    words = list(sys.argv[1:] if argv is None else argv)
    for place, word in enumerate(words[:-1]):
        if words[place + 1] == extra[0] and place > 0 and words[place - 1] in ("--set", "--vary"):
            return f" (a value with spaces needs quotes: {words[place - 1]} \"{word} {' '.join(extra)}\")"
    return ""


@contextlib.contextmanager
def _sigterm_interrupts():
    """SIGTERM (a batch scheduler's stop) interrupts as Ctrl-C does, so that a run's checkpoint is kept; either
    is heard at least once (:class:`_Stop`).  A Ctrl-C the shell has the command ignore stays ignored."""
    if threading.current_thread() is not threading.main_thread():      # only the main thread sets handlers
        yield
        return
    stop = _Stop()
    previous = {signum: signal.signal(signum, stop.handler) for signum in (signal.SIGINT, signal.SIGTERM)
                if signal.getsignal(signum) is not signal.SIG_IGN}
    try:
        yield
    except KeyboardInterrupt:
        stop.heard()
        previous = {signum: _stopping(handler) for signum, handler in previous.items()}
        raise
    finally:
        stop.heard()
        for signum, handler in previous.items():
            signal.signal(signum, handler)


class _Stop:
    """A stop signal raises KeyboardInterrupt in the main thread.  Python drops an exception raised inside a
    ctypes callback (llvmlite calls one while numba compiles), which would lose the stop: the signal is sent
    again every REPEAT_S until the command has heard it.  While a KeyboardInterrupt is being handled (a
    checkpoint or a partial output being saved) a stop raises nothing: the work of stopping is not stopped."""

    REPEAT_S = 0.5

    def __init__(self):
        self.done, self.repeating = threading.Event(), False

    def handler(self, signum, frame):
        if not self.repeating:
            self.repeating = True
            threading.Thread(target=self._repeat, args=(signum,), daemon=True).start()
        if not isinstance(sys.exc_info()[1], KeyboardInterrupt):
            raise KeyboardInterrupt

    def _repeat(self, signum):
        while not self.done.wait(self.REPEAT_S):
            os.kill(os.getpid(), signum)

    def heard(self):
        self.done.set()


def _stopping(handler):
    """The handler a stop signal keeps once the command is stopping: ignored when this process is the command,
    so that the same stop delivered again (LLVM's handler, met while numba compiles, raises it once more) does
    not kill it before it exits 130; ``handler`` when ``main`` runs inside another program."""
    return signal.SIG_IGN if _COMMAND else handler


def _run(args):
    from .checkpoint import Checkpoint
    from .reports import painter, write_run
    from .rundir import RunDirectory
    from .runner import run_scenario
    from .scenarios import load_scenario

    scenario = load_scenario(args.scenario, args.overrides)
    for note in scenario.notes:
        print(note, file=sys.stderr)
    out = Path(args.out or Path("runs") / scenario.name)
    # the painter is forked before the lock is taken, so that it never holds it
    with painter(scenario.params.output.plots) as paint, RunDirectory(out, force=args.force) as run_dir:
        scenario.checkpoint = Checkpoint(run_dir.checkpoint, args.resume, scenario.data)
        if args.resume and not os.path.lexists(run_dir.checkpoint):
            print(f"no checkpoint at {run_dir.checkpoint}: starting from the beginning", file=sys.stderr)
        elif os.path.lexists(run_dir.checkpoint) and not args.resume:
            print(f"{run_dir.checkpoint} holds an interrupted run: starting from the beginning "
                  "(--resume continues it)", file=sys.stderr)
        try:
            result = run_scenario(scenario)
        except IntegrationError as exc:
            _keep_partial(run_dir, exc, out)
            raise
        try:
            run_dir.commit(lambda d: write_run(result, d, painter=paint))
        except SpinorbitError:
            if not run_dir.staged():                    # none of the finished run on disk: keep it elsewhere
                _rescue(result, scenario.name)
            raise
        scenario.checkpoint.discard()                   # the run is whole: nothing left to resume
    verdict = result.summary["verdict"]
    print(verdict["headline"])
    if verdict.get("note"):
        print(f"  ({verdict['note']})")
    plots = sorted(p.name for p in out.glob("*.png"))
    print(f"wrote {out}/ (summary.json, timeseries.ecsv, report.md{''.join(', ' + name for name in plots)})")
    for key, value in result.summary.get("comparison", {}).items():
        print(f"  {key} = {value:.6g}" if isinstance(value, float) else f"  {key} = {value}")
    for key, reason in result.summary.get("not_measured", {}).items():
        print(f"  {key}: {reason}")
    return EXIT_VERDICT_FAIL if args.strict and verdict["result"] == "fail" else 0


def _rescue(result, name):
    """Write a finished run that its --out could not take into a new private temporary directory."""
    import tempfile

    from .reports import write_run

    try:
        where = tempfile.mkdtemp(prefix=f"spinorbit-{name}-")
        write_run(result, where)
    except OSError as exc:
        print(f"the finished run could not be written anywhere ({exc.strerror or exc})", file=sys.stderr)
        return
    print(f"the finished run is written to {where}/ instead", file=sys.stderr)


def _keep_partial(run_dir, exc, out):
    """Write a failed integration's partial output (beside a good run); a failure to write it is said in
    one line and never hides the integration's own error."""
    from .reports import write_run

    partial = getattr(exc, "result", None)
    if partial is None:
        return
    try:
        where = run_dir.fail(lambda d: write_run(partial, d, status="failed", error=exc))
    except (SpinorbitError, OSError) as error:
        print(f"the partial output could not be written ({error})", file=sys.stderr)
        return
    kept = "" if where == run_dir.out else f"; the previous run in {out}/ is kept"
    print(f"partial output written to {where}/{kept}", file=sys.stderr)


def _sweep(args):
    from .sweep import grid, run_sweep

    varied = grid(args.vary)
    out = Path(args.out or Path("runs") / f"{Path(args.scenario).stem}-sweep")
    records = run_sweep(args.scenario, varied, out, args.scheduler, args.overrides, force=args.force)
    failed = [r for r in records if r["status"] != "ok"]
    print(f"sweep: {len(records)} runs, {len(failed)} failed; table in {out}/sweep.csv")
    for record in failed:
        print(f"  failed {record['overrides']}: {record['error']}", file=sys.stderr)
    return 1 if failed else 0


def _bench(args):
    from .bench import bench_scenario

    methods = args.methods.split(",") if args.methods else None
    rows, paths = bench_scenario(args.scenario, methods, args.out, args.budget, args.overrides,
                                 force=args.force)
    print(f"bench: {len(rows)} runs; wrote {', '.join(str(p) for p in paths)}")
    return 0


def _cache(action):
    from ..base.linker import cache
    from ..solutions import store
    from . import caches

    if action == "clear":
        print("\n".join(caches.clear()))
        return 0
    print("\n".join(caches.listing()))
    for line in _solution_lines(store.entries()):
        print(line)
    print(f"({cache.ENVIRONMENT} moves them; `spinorbit cache clear` empties them; the stored solutions are kept "
          f"within {store.LIMIT['bytes'] / 1e9:g} GB, the least recently written removed first)")
    return 0


class _ExportHelp(argparse.Action):
    """``spinorbit export --help``: the help, with the scene kinds whose solutions SPICE kernels carry (read
    off every scene's ``stored`` only when asked: the other commands do not import the scenes)."""

    def __call__(self, parser, namespace, values, option_string=None):
        parser.epilog = (f"exportable scene kinds: {', '.join(_exportable())} (a built-in scene of one of these "
                         "kinds, or a scenario file of one; spinorbit list names them)")
        parser.print_help()
        parser.exit()


class _AtHelp(argparse.Action):
    """``spinorbit at --help``: the help, with the bodies the scenes answer for and what each gives (read off the
    scenes, spinorbit.edge.api.answers, only when asked: the other commands do not import them)."""

    def __call__(self, parser, namespace, values, option_string=None):
        from . import api

        said = "; ".join(f"{a.body}: {a.about}" for a in sorted(api.answers().values(), key=lambda a: a.body or "")
                         if a.body)
        parser.epilog = f"bodies: {said}"
        parser.print_help()
        parser.exit()


def _exportable():
    from ..scenes import stored_kinds

    return sorted(kind for kind, stored in stored_kinds().items() if stored.kernels)


def _export(args):
    """Write the SPICE kernels of exactly the scenario's model over its span (solutions.for_export)."""
    import time

    from ..base.errors import InputError
    from ..solutions import for_export
    from .scenarios import load_scenario

    scenario = load_scenario(args.scenario, args.overrides)
    if scenario.scene.stored is None or not scenario.scene.stored.kernels:     # refused before anything is integrated
        raise InputError("scene", scenario.kind, f"a scene whose solution SPICE kernels carry: {_exportable()}")
    _out_folder(args.out)
    solution = for_export(scenario)
    started = time.perf_counter()
    from ..scene.params import values_of

    written = solution.export(args.out, asked=values_of(scenario.params))
    wall = time.perf_counter() - started
    for path in written["files"]:
        print(f"wrote {path} ({os.path.getsize(path) / 1e6:.3g} MB)")
    fit = ", ".join(f"{k} {v:.2g}" for k, v in {**solution.fit_error, **written["fit_error"]}.items())
    frames = ", ".join(written["frames"].values())
    print(f"{solution!r}\nframes: {frames or 'none'}; written in {wall:.2f} s; fit errors: {fit}")
    return 0


def _out_folder(given):
    """Make export's --out folder (before anything is integrated); a path the system cannot hold (a name
    longer than NAME_MAX, the whole longer than PATH_MAX) is an InputError naming --out and the limits."""
    import errno

    from ..base.errors import InputError

    folder = Path(given)
    try:
        folder.mkdir(parents=True, exist_ok=True)
        probe = folder / f".earth_moon_coupled_moon.probe.bpc.tmp-{os.getpid()}"   # longer than any kernel's
        probe.touch()
        probe.unlink()
    except OSError as exc:
        if exc.errno != errno.ENAMETOOLONG:
            raise
        existing = next(p for p in (folder.absolute(), *folder.absolute().parents) if os.path.exists(p))
        raise InputError("--out", given, f"a folder path of at most {os.pathconf(existing, 'PC_PATH_MAX')} "
                                         f"bytes, each name in it at most {os.pathconf(existing, 'PC_NAME_MAX')} "
                                         f"(this one: {len(os.fsencode(folder.absolute()))} bytes)") from None


def _at(args):
    """``spinorbit at BODY DATE ...``: the API's answer at the dates, printed as CSV or ECSV."""
    import io

    from astropy.time import Time

    from ..base.errors import InputError
    from . import api

    if args.body not in api.bodies():
        raise InputError("BODY", args.body, f"one of {list(api.bodies())} (the bodies the scenes answer for)")
    try:
        times = Time(args.dates, scale=args.scale)
    except ValueError:
        raise InputError("DATE", args.dates, "ISO dates or times, e.g. 2027-03-01 or 2027-03-01T12:00:00") from None
    table = api.orientation(args.body, times)
    table["time"] = table["time"].isot
    table.rename_column("time", f"time_{args.scale}")
    if args.format == "csv":
        table = _flat_columns(table)
        for name in table.colnames:
            unit = getattr(table[name], "unit", None)
            if unit is not None and str(unit):
                table.rename_column(name, f"{name} [{unit}]")
    text = io.StringIO()
    table.write(text, format="ascii.ecsv" if args.format == "ecsv" else "ascii.csv")
    sys.stdout.write(text.getvalue())
    return 0


def _flat_columns(table):
    """A copy of ``table`` whose columns of arrays (the Earth's GCRS-to-CIRS matrix) are one column per element,
    ``<name>_<row><column>`` from 1, in their place: CSV holds one value a cell."""
    import numpy as np

    table = table.copy()
    for name in [n for n in table.colnames if table[n].ndim > 1]:
        column, at = table[name], table.colnames.index(name)
        table.remove_column(name)
        for k, index in enumerate(np.ndindex(column.shape[1:])):
            table.add_column(column[(slice(None), *index)], name=f"{name}_{''.join(str(i + 1) for i in index)}",
                             index=at + k)
    return table


def _solution_lines(entries):
    """One line per stored solution: the scene, its span (Julian years), its size, its file."""
    lines = []
    for path, scene, span, size in entries:
        years = "span unreadable" if span is None else "–".join(f"{2000.0 + t / 365.25:.2f}" for t in span)
        lines.append(f"  solution {scene}: {years}, {size / 1e6:.3g} MB ({path.name})")
    return lines


def _show(scene):
    import textwrap

    from .key_table import key_table

    heading, rows = key_table(scene)
    width = _width()
    print(textwrap.fill(heading, width, subsequent_indent="  "))
    print()
    for line in _columns(rows, width, caps=(34, 26, 24, 8, 22)):
        print(line)
    return 0


def _width():
    """The terminal's width (COLUMNS where set); no limit when stdout is not a terminal (a pipe, a file): one
    line per row there, for grep."""
    import shutil

    if "COLUMNS" not in os.environ and not sys.stdout.isatty():
        return 1 << 16
    return shutil.get_terminal_size().columns


def _columns(rows, width, caps, narrowest=40):
    """Lines of ``rows`` (tuples of texts) in columns: each but the last as wide as its widest cell up to its
    cap, the last filling the rest of ``width`` (below the row, indented, when that leaves it under
    ``narrowest``); a cell wider than its column wraps onto the next lines, nothing is cut."""
    import textwrap

    widths = [min(cap, max(len(row[i]) for row in rows)) for i, cap in enumerate(caps)]
    last = width - sum(w + 1 for w in widths)
    below = last < narrowest
    for row in rows:
        cells = [textwrap.wrap(text, w, break_on_hyphens=False) or [""] for text, w in zip(row, widths)]
        if not below:
            cells.append(textwrap.wrap(row[-1], last, break_long_words=False, break_on_hyphens=False) or [""])
        for depth in range(max(len(cell) for cell in cells)):
            parts = [(cell[depth] if depth < len(cell) else "").ljust(w) for cell, w in zip(cells, widths + [0])]
            yield " ".join(parts).rstrip()
        if below and row[-1]:
            yield from textwrap.wrap(row[-1], max(narrowest, width), initial_indent="    ",
                                     subsequent_indent="    ", break_long_words=False,
                                     break_on_hyphens=False)


def _list(folder):
    """One line per scenario file under ``folder`` (None: the built-in scenes, by the name ``run`` takes):
    only regular files are opened (a FIFO, a device or a link to one is listed as such, never read), and at
    most MAX_LISTED_BYTES of each."""
    import tomllib

    from . import catalogue

    if folder is None:
        folder, builtin = catalogue.folder(), True
    else:
        folder, builtin = Path(folder), False
    files = sorted(_toml_files(folder))
    if not files:
        print(f"no scenarios in {_printable(folder)}/")
        return 0
    rows = []
    for path in files:
        try:
            scene = tomllib.loads(_read_small(path).decode("utf-8")).get("scene", {})
        except OSError as exc:
            scene = {"title": f"({exc.strerror or exc})"}
        except (UnicodeDecodeError, ValueError, RecursionError):     # TOMLDecodeError is a ValueError
            scene = {"title": "(not a readable UTF-8 TOML file)"}
        scene = scene if isinstance(scene, dict) else {}
        kind, title = (" ".join(str(scene.get(key, default)).split())
                       for key, default in (("kind", "?"), ("title", "")))
        name = path.relative_to(folder)
        rows.append((name.with_suffix("").as_posix() if builtin else _printable(name), kind, title))
    for line in _columns(rows, _width(), caps=(48, 28)):
        print(line)
    return 0


def _printable(path):
    """A path as text, undecodable bytes shown as escapes."""
    return str(path).encode("utf-8", "backslashreplace").decode()


def _toml_files(folder):
    """Paths ending in .toml under ``folder``, without following links to folders."""
    for directory, _, names in os.walk(folder):
        for name in names:
            if name.endswith(".toml"):
                yield Path(directory) / name


def _read_small(path):
    """The bytes of a regular file (following a link to one), never opening anything else."""
    import stat

    if not stat.S_ISREG(os.stat(path).st_mode):
        raise OSError(0, "not a regular file")
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_CLOEXEC)
    with os.fdopen(fd, "rb") as f:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise OSError(0, "not a regular file")
        if info.st_size > MAX_LISTED_BYTES:
            raise OSError(0, f"{info.st_size} bytes, not a scenario")
        return f.read(MAX_LISTED_BYTES)


def console():
    """The ``spinorbit`` command: :func:`main`, then ``gc.freeze()`` so that the interpreter's exit does not
    walk the million objects numba and astropy leave behind (0.4 s of the Moon's 6-s run).  Not in
    ``main``, which tests and notebooks call in their own process."""
    global _COMMAND
    _COMMAND = True
    try:
        code = main()
    except BrokenPipeError:                  # `spinorbit list | head`: the reader left; say nothing more
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 141
    for stop in (signal.SIGINT, signal.SIGTERM):     # the work is done and said: a stop now changes nothing
        signal.signal(stop, signal.SIG_IGN)
    gc.freeze()
    return code


if __name__ == "__main__":
    sys.exit(console())
