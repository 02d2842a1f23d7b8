"""The drawing every family shares: curves against x, stacked panels, thinning long series to the pixels
that show, plain log labels and a figure's title."""
from functools import partial

import numpy as np


def plot_series(x, ys, xlabel, ylabel, labels=None, logy=False):
    """One or more curves against x."""
    return partial(_series, x=x, ys=np.atleast_2d(ys), xlabel=xlabel, ylabel=ylabel, labels=labels, logy=logy)


def _series(fig, x, ys, xlabel, ylabel, labels, logy):
    ax = fig.add_subplot()
    for i, y in enumerate(ys):
        ax.plot(*thinned(x, y), lw=0.8, label=None if labels is None else labels[i])
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    if logy:
        ax.set_yscale("log")
        plain_log_labels(ax)
    if labels is not None:
        ax.legend()
    ax.grid(alpha=0.3)


def plot_panels(x, panels, xlabel, sharex=True):
    """Stacked panels sharing x (NaN leaves a panel's part out: ``sharex=False`` then fits each to its own);
    ``panels`` = [(ys, labels, ylabel), ...]; the second curve of a panel is drawn dashed over the first (a
    reference overlaid)."""
    draw = partial(_panels, x=x, panels=panels, xlabel=xlabel, sharex=sharex)
    draw.figsize = (8, 1.0 + 2.2 * len(panels))          # read by reports.write_plots
    return draw


def _panels(fig, x, panels, xlabel, sharex):
    axes = fig.subplots(len(panels), 1, sharex=sharex)
    for ax, (ys, labels, ylabel) in zip(np.atleast_1d(axes), panels):
        for i, (y, label) in enumerate(zip(np.atleast_2d(ys), labels)):
            shown = np.isfinite(y)
            ax.plot(*thinned(np.asarray(x)[shown], y[shown]), lw=1.2 if i == 0 else 0.9, ls="-" if i == 0 else "--",
                    label=label)
        ax.set_ylabel(ylabel)
        # above the panel, off the curves (which run to both edges)
        ax.legend(fontsize=8, loc="lower right", bbox_to_anchor=(1.0, 1.0), ncol=len(labels), frameon=False,
                  borderaxespad=0.1, handlelength=1.5)
        ax.grid(alpha=0.3)
    np.atleast_1d(axes)[-1].set_xlabel(xlabel)


COLUMNS = 1000      # intervals across a plot's width: more than its axes' pixels (~740 at 8 in, 110 dpi)


def thinned(x, y, log=False):
    """(x, y) without the points that cannot show: of each run of consecutive points within one of COLUMNS
    equal intervals of x (of log10 x), only the lowest and the highest (in their order) and the ends are
    kept.  Drawn at the figure's width the line covers the same pixels; Agg draws ~10x fewer points
    (the Moon's physical libration, 2 x 27,393 points: 0.45 -> 0.19 s)."""
    x, y = np.asarray(x), np.asarray(y)
    if x.size <= 4 * COLUMNS:
        return x, y
    u = np.log10(x) if log else x
    column = ((u - u[0]) / (u[-1] - u[0]) * COLUMNS).astype(int)
    run = np.concatenate([[0], np.cumsum(column[1:] != column[:-1])])
    order = np.lexsort((y, run))                       # by run, then by y: each run's lowest first
    first = np.flatnonzero(np.diff(run[order], prepend=-1))
    last = np.append(first[1:] - 1, y.size - 1)
    keep = np.unique(np.concatenate([order[first], order[last], [0, y.size - 1]]))
    return x[keep], y[keep]


def plain_log_labels(ax):
    """Label the decades of ``ax``'s log axes as plain numbers ("100", "0.001"), not mathtext's 10^k,
    which costs ~40 ms a label to parse (0.35 s of the Moon's spectrum figure)."""
    from matplotlib.ticker import FuncFormatter

    for axis in (ax.xaxis, ax.yaxis):
        if axis.get_scale() == "log":
            axis.set_major_formatter(FuncFormatter(lambda value, _: f"{value:g}"))


def titled(draw, title):
    """Give a drawing function the plot title reports.write_plots puts above it (with scene and span)."""
    draw.title = title
    return draw
