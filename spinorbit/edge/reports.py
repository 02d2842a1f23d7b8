"""Write a run directory: summary.json, timeseries.ecsv, report.md and PNG plots.

Every file is written to a temporary name and renamed into place, so a run
that fails half-way never leaves a truncated file, and earlier files stay.
"""
import io
import json
import math
import os
import pickle
import signal
import sys
import textwrap
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from ..scene.schema import dotted_items


def write_run(result, out_dir, status="ok", error=None, painter=None):
    """Write everything a RunResult holds into ``out_dir``; return the list of paths.

    painter: a :class:`Painter`, which draws the plots in its own process while this one writes
    the ECSV; without one they are drawn here.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    summary = {**result.summary, "status": status}
    if error is not None:
        summary["error"] = str(error)
    text = json.dumps(_jsonable(summary), indent=2, allow_nan=False) + "\n"
    written = [_atomic(out / "summary.json", lambda p: p.write_text(text))]
    drawing = result.scenario.params.output.plots
    if drawing and painter is not None:
        painter.draw(result.figures, summary, out)
    if result.table is not None and len(result.table):
        written.append(_atomic(out / "timeseries.ecsv", lambda p: write_ecsv(result.table, p)))
    if drawing and painter is not None:
        plots = painter.wait()
    else:
        plots = write_plots(result.figures, summary, out) if drawing else []
    written += plots
    written.append(_atomic(out / "report.md", lambda p: p.write_text(report_markdown(summary, plots))))
    return written


def write_ecsv(table, path):
    """``table`` as ECSV at ``path``.  astropy writes the header (the schema, units, meta); a body of plain
    numbers (every column serialised as one 1-d float64 or integer column: Column, Quantity, Time in a
    numeric format) is written here as astropy writes it, ``str`` of each value, the same bytes without
    astropy's per-cell calls (the Moon's 27,393 x 21 table: 2.1 -> 0.5 s); any other table astropy
    writes whole."""
    header = io.StringIO()
    table[:0].write(header, format="ascii.ecsv")
    columns = [np.asarray(getattr(table[name], "value", table[name])) for name in table.colnames]
    plain = all(type(c) is np.ndarray and c.ndim == 1 and (c.dtype == np.float64 or c.dtype.kind in "iu")
                for c in columns)
    if not plain or header.getvalue().splitlines()[-1] != " ".join(table.colnames):
        table.write(path, format="ascii.ecsv", overwrite=True)
        return
    with open(path, "w", encoding="utf-8", newline="") as file:
        file.write(header.getvalue())
        file.writelines(" ".join(map(repr, row)) + "\n" for row in zip(*(c.tolist() for c in columns)))


class Painter:
    """A child process that draws one run's figures.  Forked before the run, it imports matplotlib and
    draws a throwaway figure while the run computes (1.2 s of the 2.1 s it took to draw the Moon's
    figures after the run); then it draws what :meth:`draw` sends while this process writes the
    table.  Use :func:`painter`, which ends the child on leaving if it is still running."""

    def __init__(self, context):
        sys.stdout.flush()                 # nothing buffered is written twice by the child
        sys.stderr.flush()
        theirs, self._conn = context.Pipe(duplex=False)
        self._child = context.Process(target=_paint, args=(theirs, self._conn), daemon=True)
        # Ctrl-C and SIGTERM are held until the child has its own handlers: one arriving between the fork
        # and the child's code would run this process's handlers there and unwind through its frames
        held = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT, signal.SIGTERM})
        try:
            self._child.start()
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, held)
        theirs.close()
        self._paths = []

    @property
    def pid(self):
        """The child's process id."""
        return self._child.pid

    def draw(self, figures, summary, out):
        """Send the figures (name -> draw(fig), picklable: spinorbit.plots) to be drawn into ``out``."""
        self._paths = [Path(out) / f"{name}.png" for name in figures]
        self._conn.send_bytes(pickle.dumps((figures, summary, Path(out))))  # multiprocessing's pickler
                                                                              # drops a partial's attributes

    def wait(self):
        """The PNG paths, once the child has drawn them."""
        self._child.join()
        if self._child.exitcode != 0:
            raise RuntimeError(f"drawing the plots failed (exit code {self._child.exitcode})")
        return self._paths

    def end(self):
        """Close the pipe and end the child if it still runs."""
        self._conn.close()
        if self._child.is_alive():
            self._child.kill()
        self._child.join()


@contextmanager
def painter(plots=True):
    """A :class:`Painter` forked now, or None without plots or where the platform has no fork."""
    import multiprocessing

    forks = "fork" in multiprocessing.get_all_start_methods()
    started = Painter(multiprocessing.get_context("fork")) if plots and forks else None
    try:
        yield started
    finally:
        if started is not None:
            started.end()


def _paint(conn, parents_end):
    """The Painter's child: prepare matplotlib, then draw the one job sent (or end when the pipe closes)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)      # the parent answers Ctrl-C, and ends this child
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT, signal.SIGTERM})
    parents_end.close()              # else the parent's death, which closes its copy, would not end the pipe
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(2, 2))          # a throwaway log-log figure: fonts, mathtext's parser, the PNG writer
    fig.add_subplot().loglog([1, 10], [1, 10])
    fig.savefig(io.BytesIO(), format="png")
    plt.close(fig)
    try:
        figures, summary, out = pickle.loads(conn.recv_bytes())
    except EOFError:
        return
    write_plots(figures, summary, out)


def write_plots(figures, summary, out):
    """Draw ``figures`` (name -> draw(fig)) into ``out``/<name>.png, titled with the summary's scene and span."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    paths = []
    span = summary.get("span", {}).get("years", "")
    for name, draw in figures.items():
        width, height = getattr(draw, "figsize", (8, 4.5))
        fig = plt.figure(figsize=(width, height))
        draw(fig)
        title = getattr(draw, "title", name.replace("_", " "))
        heading = textwrap.wrap(f"{summary.get('scene', '')}: {title} ({span})", int(11 * width))
        fig.suptitle("\n".join(heading), fontsize=11)
        # fixed margins (inches) instead of tight_layout, which measures every tick label (1.7 s of 4 figures)
        top = 0.3 + 0.2 * len(heading)
        fig.subplots_adjust(left=1.0 / width, right=1 - 0.25 / width, bottom=0.55 / height, top=1 - top / height,
                            hspace=0.3 * 4.5 / height)
        paths.append(_atomic(out / f"{name}.png", lambda p: fig.savefig(p, dpi=110, format="png")))
        plt.close(fig)
    return paths


SKIP = ("scene", "kind", "title", "status", "error", "verdict", "provenance")


def report_markdown(summary, plots):
    status = ("the run finished; the verdict says whether the result meets its tolerance" if summary["status"] == "ok"
              else "the integration stopped before the end; what it had is written, nothing is judged")
    lines = [f"# {summary.get('title') or summary['scene']}", "",
             f"Scene `{summary['scene']}` (kind `{summary['kind']}`), status **{summary['status']}** ({status}).", ""]
    if "error" in summary:
        lines += [f"Error: {summary['error']}", ""]
    if "verdict" in summary:
        lines += verdict_markdown(summary["verdict"])
    lines += ["## Numbers", "", "| quantity | value |", "|---|---|"]
    tables = []
    for key, value in dotted_items({k: v for k, v in summary.items() if k not in SKIP}, is_table=_is_matrix):
        if isinstance(value, list) and value and all(isinstance(row, dict) for row in value):
            tables.append((key, value))
        elif _is_matrix(value):
            tables.append((key, _matrix_rows(value)))
        else:
            lines.append(f"| {key} | {_fmt(value)} |")
    lines.append("")
    for key, rows in tables:
        lines += [f"### {key}", "", *rows_markdown(rows), ""]
    lines += [f"![{p.stem}]({p.name})" for p in plots]
    if "provenance" in summary:
        lines += ["", "## Provenance", "", "| item | value |", "|---|---|"]
        lines += [f"| {key} | {_fmt(value)} |" for key, value in dotted_items(summary["provenance"])
                  if not key.startswith("settings.")]
        lines.append("")
    return "\n".join(lines) + "\n"


def verdict_markdown(verdict):
    """The headline and one row per check: figure, tolerance, result, where the tolerance comes from."""
    lines = [f"**Verdict: {verdict['result']}** — {verdict['headline'].split(' — ', 1)[-1]}", ""]
    if verdict.get("note"):
        lines += [f"Note: {verdict['note']}.", ""]
    if verdict["checks"]:
        lines += ["| check | figure | tolerance | result | tolerance from |", "|---|---|---|---|---|"]
        for c in verdict["checks"]:
            figure = c.get("reason") if c["figure"] is None else f"{_fmt(c['figure'])}{c['unit']}"
            if "expected" in c and c["figure"] is not None:
                figure = f"{_fmt(c['expected'] + c['figure'])}{c['unit']} (expected {_fmt(c['expected'])}{c['unit']})"
            lines.append(f"| {c['label']} | {figure} | {_fmt(c['tolerance'])}{c['unit']} | {c['result']} | "
                         f"{c['source']} |")
        lines.append("")
    return lines


def _is_matrix(value):
    """A dict of dicts of dicts of numbers (e.g. terms -> parts -> series): drawn as one table."""
    return (isinstance(value, dict) and value and all(isinstance(v, dict) and v for v in value.values())
            and all(isinstance(w, dict) and w and all(isinstance(x, (int, float)) for x in w.values())
                    for v in value.values() for w in v.values()))


def _matrix_rows(value):
    """Rows {"": "<key> <part>", **series} of a matrix (:func:`_is_matrix`)."""
    return [{"": f"{name} {part}", **series} for name, parts in value.items() for part, series in parts.items()]


def rows_markdown(rows):
    """A list of dicts as a table; a ``fitted_X`` beside a ``published_X`` gets a difference column."""
    columns = list(dict.fromkeys(k for row in rows for k in row))
    pairs = [c for c in columns if c.startswith("fitted_") and "published_" + c[len("fitted_"):] in columns]
    header = columns + [f"fitted − published ({c[len('fitted_'):]})" for c in pairs]
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    for row in rows:
        cells = [_fmt(row.get(c, "")) for c in columns]
        for c in pairs:
            fitted, published = row.get(c), row.get("published_" + c[len("fitted_"):])
            both = all(isinstance(v, (int, float)) for v in (fitted, published))
            cells.append(_fmt(float(fitted) - float(published)) if both else "")
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def _fmt(value):
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, list) and len(value) > 8:
        return f"[{len(value)} values]"
    return str(value)


def _jsonable(value):
    if isinstance(value, dict):
        return {str(k): _jsonable(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_jsonable(v) for v in value]
    if isinstance(value, np.ndarray):
        return _jsonable(value.tolist())
    if isinstance(value, (np.floating, float)):
        value = float(value)
        return value if math.isfinite(value) else None     # runner.mark_unmeasured says why
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, np.bool_):
        return bool(value)
    return value


def _atomic(path, write):
    tmp = path.with_name(f".{path.name}.tmp")
    write(tmp)
    os.replace(tmp, path)
    return path
