"""Write a run directory: summary.json, timeseries.ecsv, report.md and PNG plots.

Every file is written to a temporary name and renamed into place, so a run
that fails half-way never leaves a truncated file, and earlier files stay.
"""
import json
import math
import os
from pathlib import Path

import numpy as np

from .schema import dotted_items


def write_run(result, out_dir, status="ok", error=None, fork_plots=False):
    """Write everything a RunResult holds into ``out_dir``; return the list of paths.

    fork_plots: draw the plots in a forked child process while this one writes the
    ECSV (both are Python-bound; on two cores this halves the writing time).  For a
    single-threaded caller such as the command line, where fork is available.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    summary = {**result.summary, "status": status}
    if error is not None:
        summary["error"] = str(error)
    text = json.dumps(_jsonable(summary), indent=2, allow_nan=False) + "\n"
    written = [_atomic(out / "summary.json", lambda p: p.write_text(text))]
    context = _fork_context() if result.scenario["output.plots"] and fork_plots else None
    drawing = context is not None
    if drawing:
        child = context.Process(target=write_plots, args=(result, out), daemon=True)
        child.start()
    if result.table is not None and len(result.table):
        written.append(_atomic(out / "timeseries.ecsv", lambda p: result.table.write(p, format="ascii.ecsv", overwrite=True)))
    if drawing:
        child.join()
        if child.exitcode != 0:
            raise RuntimeError(f"drawing the plots failed (exit code {child.exitcode})")
        plots = [out / f"{name}.png" for name in result.figures]
    else:
        plots = write_plots(result, out) if result.scenario["output.plots"] else []
    written += plots
    written.append(_atomic(out / "report.md", lambda p: p.write_text(report_markdown(summary, plots))))
    return written


def _fork_context():
    """multiprocessing's fork context, or None where the platform has no fork."""
    import multiprocessing

    return multiprocessing.get_context("fork") if "fork" in multiprocessing.get_all_start_methods() else None


def write_plots(result, out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    paths = []
    summary = result.summary
    span = summary.get("span", {}).get("years", "")
    for name, draw in result.figures.items():
        width, height = getattr(draw, "figsize", (8, 4.5))
        fig = plt.figure(figsize=(width, height))
        draw(fig)
        title = getattr(draw, "title", name.replace("_", " "))
        fig.suptitle(f"{summary.get('scene', '')}: {title} ({span})", fontsize=11)
        # fixed margins (inches) instead of tight_layout, which measures every tick label (1.7 s of 4 figures)
        fig.subplots_adjust(left=1.0 / width, right=1 - 0.25 / width, bottom=0.55 / height, top=1 - 0.5 / height,
                            hspace=0.3 * 4.5 / height)
        paths.append(_atomic(out / f"{name}.png", lambda p: fig.savefig(p, dpi=110, format="png")))
        plt.close(fig)
    return paths


SKIP = ("scene", "kind", "title", "status", "error", "verdict", "provenance")


def report_markdown(summary, plots):
    lines = [f"# {summary.get('title') or summary['scene']}", "",
             f"Scene `{summary['scene']}` (kind `{summary['kind']}`), status **{summary['status']}** "
             "(the run finished; the verdict says whether the result meets its tolerance).", ""]
    if "error" in summary:
        lines += [f"Error: {summary['error']}", ""]
    if "verdict" in summary:
        lines += verdict_markdown(summary["verdict"])
    lines += ["## Numbers", "", "| quantity | value |", "|---|---|"]
    tables = []
    for key, value in dotted_items({k: v for k, v in summary.items() if k not in SKIP}):
        if isinstance(value, list) and value and all(isinstance(row, dict) for row in value):
            tables.append((key, value))
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
            figure = c.get("reason") if c["figure"] is None else _fmt(c["figure"])
            if "expected" in c and c["figure"] is not None:
                figure = f"{_fmt(c['expected'] + c['figure'])} (expected {_fmt(c['expected'])})"
            lines.append(f"| {c['label']} | {figure} | {_fmt(c['tolerance'])}{c['unit']} | {c['result']} | "
                         f"{c['source']} |")
        lines.append("")
    return lines


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
        return value if math.isfinite(value) else None     # results.mark_unmeasured says why
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
