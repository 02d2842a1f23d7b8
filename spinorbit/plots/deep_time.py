"""Deep time: obliquity and climatic precession against a reference (La2004), their spectra with the
Milankovitch periods marked, and a sweep's obliquity band."""
from functools import partial

import numpy as np

from .common import plain_log_labels, plot_panels, thinned, titled

# The astronomical periods of the climate record (kyr): obliquity, climatic precession, eccentricity.
MILANKOVITCH_KYR = {"41": 41.0, "23": 23.0, "19": 19.0, "100": 100.0, "405": 405.0}


def deep_time(t_kyr, model, reference, name):
    """Obliquity (deg) and climatic precession e sin(varpi_bar) against kyr from J2000, the reference (e.g.
    La2004) dashed over the model, and below each the model minus the reference; ``model``/``reference`` =
    {"obliquity_deg": .., "climatic_precession": ..} (``reference`` None: the model alone)."""
    panels = []
    for key, label in (("obliquity_deg", "obliquity [deg]"), ("climatic_precession", "e sin(ϖ̄)")):
        if reference is None:
            panels.append(([model[key]], ["model"], label))
            continue
        panels += [([model[key], reference[key]], ["model", name], label),
                   ([model[key] - reference[key]], [f"model − {name}"], f"{label.split(' [')[0]}: "
                    f"model − {name}" + (" [deg]" if "[deg]" in label else ""))]
    return titled(plot_panels(t_kyr, panels, "kyr from J2000"),
                  "obliquity and climatic precession" + ("" if reference is None else f" ({name} dashed)"))


DEEP_TIME_LABELS = {"obliquity_deg": "obliquity [deg]", "climatic_precession": "e sin(ϖ̄)",
                    "eccentricity": "eccentricity"}


def deep_time_spectra(t_kyr, model, reference, name):
    """Amplitude spectra of the obliquity, the climatic precession and the eccentricity (model, and the
    reference dashed), the periods of MILANKOVITCH_KYR marked."""
    from ..analysis.spectrum import amplitude_spectrum

    series = {}
    for key in DEEP_TIME_LABELS:
        curves = [amplitude_spectrum(t_kyr, model[key])]
        if reference is not None:
            curves.append(amplitude_spectrum(t_kyr, reference[key]))
        series[key] = curves
    span = abs(t_kyr[-1] - t_kyr[0])
    draw = partial(_deep_time_spectra, series=series, span=span, name=name)
    draw.figsize = (8, 8.5)
    return titled(draw, "spectra, the periods marked in kyr")


def _deep_time_spectra(fig, series, span, name):
    axes = fig.subplots(len(series), 1, sharex=True)
    for ax, (key, curves) in zip(axes, series.items()):
        for i, (period, amplitude) in enumerate(curves):
            keep = period <= span / 2
            ax.loglog(*thinned(period[keep], amplitude[keep], log=True), lw=1.0 if i == 0 else 0.8,
                      ls="-" if i == 0 else "--", label="model" if i == 0 else name)
        marked = {text: period for text, period in MILANKOVITCH_KYR.items() if period <= span / 2}
        for period in marked.values():
            ax.axvline(period, color="0.6", lw=0.6, ls=":")
        if ax is axes[0] and marked:                 # the periods named once, above the plots, off the curves
            top = ax.secondary_xaxis("top")
            top.set_xticks(list(marked.values()), [f"{text}" for text in marked], fontsize=7)
            top.tick_params(which="minor", top=False, labeltop=False)
        ax.set_ylabel(f"amplitude of {DEEP_TIME_LABELS[key]}")
        ax.legend(fontsize=8, loc="lower right")
        ax.grid(alpha=0.3, which="both")
        plain_log_labels(ax)
    axes[-1].set_xlabel("period [kyr]")


def obliquity_band(t_kyr, low, high, nominal, reference, name):
    """A sweep's obliquity band (deg, min to max over its members at each time) shaded, its first member and
    the reference (e.g. La2004 Mars) over it, against kyr from J2000; below, the band's width."""
    draw = partial(_obliquity_band, t_kyr=t_kyr, low=low, high=high, nominal=nominal, reference=reference,
                   name=name)
    draw.figsize = (8, 6)
    return titled(draw, f"obliquity: the sweep's band and {name}")


def _obliquity_band(fig, t_kyr, low, high, nominal, reference, name):
    axes = fig.subplots(2, 1, sharex=True, height_ratios=(3, 1))
    axes[0].fill_between(t_kyr, low, high, color="0.75", label="sweep (min to max)")
    axes[0].plot(*thinned(t_kyr, nominal), lw=0.8, label="first member")
    if reference is not None:
        axes[0].plot(*thinned(t_kyr[:len(reference)], reference), lw=0.8, ls="--", label=name)
    axes[0].set_ylabel("obliquity [deg]")
    axes[0].legend(fontsize=8)
    axes[1].semilogy(t_kyr, np.maximum(high - low, 1e-6), lw=0.8)
    axes[1].set_ylabel("band width [deg]")
    axes[1].set_xlabel("kyr from J2000")
    for ax in axes:
        ax.grid(alpha=0.3)
