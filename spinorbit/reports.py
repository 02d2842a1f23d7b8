"""Write a run directory: summary.json, timeseries.ecsv, report.md and PNG plots.

Every file is written to a temporary name and renamed into place, so a run
that fails half-way never leaves a truncated file, and earlier files stay.
"""
import json
import math
import os
from pathlib import Path

import numpy as np


def write_run(result, out_dir, status="ok", error=None):
    """Write everything a RunResult holds into ``out_dir``; return the list of paths."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    summary = {**result.summary, "status": status}
    if error is not None:
        summary["error"] = str(error)
    text = json.dumps(_jsonable(summary), indent=2, allow_nan=False) + "\n"
    written = [_atomic(out / "summary.json", lambda p: p.write_text(text))]
    if result.table is not None and len(result.table):
        written.append(_atomic(out / "timeseries.ecsv", lambda p: result.table.write(p, format="ascii.ecsv", overwrite=True)))
    plots = write_plots(result, out) if result.scenario["output.plots"] else []
    written += plots
    written.append(_atomic(out / "report.md", lambda p: p.write_text(report_markdown(summary, plots))))
    return written


def write_plots(result, out):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    paths = []
    for name, draw in result.figures.items():
        fig = plt.figure(figsize=(8, 4.5))
        draw(fig)
        fig.tight_layout()
        paths.append(_atomic(out / f"{name}.png", lambda p: fig.savefig(p, dpi=110, format="png")))
        plt.close(fig)
    return paths


def report_markdown(summary, plots):
    lines = [f"# {summary.get('title') or summary['scene']}", "",
             f"Scene `{summary['scene']}` (kind `{summary['kind']}`), status **{summary['status']}**.", ""]
    if "error" in summary:
        lines += [f"Error: {summary['error']}", ""]
    lines += ["| quantity | value |", "|---|---|"]
    for key, value in _flat(summary):
        if key not in ("scene", "kind", "title", "status", "error"):
            lines.append(f"| {key} | {_fmt(value)} |")
    lines.append("")
    lines += [f"![{p.stem}]({p.name})" for p in plots]
    return "\n".join(lines) + "\n"


def _flat(d, prefix=""):
    for key, value in d.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            yield from _flat(value, name + ".")
        else:
            yield name, value


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
