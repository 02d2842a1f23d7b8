"""Error against cost: a ladder of runs' maximum error against their wall time, one curve per method."""
from functools import partial

from .common import plain_log_labels


def plot_error_vs_cost(rows, errors, methods=(("rk8", "o-"), ("dop853", "s--"))):
    """Max error against wall time, log-log, one curve per method and error: ``errors`` = [(key of the
    rows, label, alpha), ...], ``rows`` as from analysis.ladder (rows that failed are left out)."""
    return partial(_error_vs_cost, rows=rows, errors=errors, methods=methods)


def _error_vs_cost(fig, rows, errors, methods):
    ax = fig.add_subplot()
    for method, marker in methods:
        sel = [r for r in rows if r["method"] == method and "failed" not in r]
        for key, label, alpha in errors:
            ax.loglog([r["wall_s"] for r in sel], [max(r[key], 1e-9) for r in sel], marker, alpha=alpha,
                      label=f"{method} {label}")
    ax.set_xlabel("wall time [s]")
    ax.set_ylabel("max attitude error [arcsec]")
    plain_log_labels(ax)
    ax.legend()
    ax.grid(alpha=0.3, which="both")
