"""A chaotic spin's Lyapunov map (the Hyperion-like stress comparison)."""
from functools import partial

import numpy as np


def plot_lyapunov_map(theta, rate, exponent, threshold):
    """Lyapunov exponent (1/T) over a grid of theta - f (rad) and rate / n at periapsis, the chaotic border
    (``threshold``) drawn."""
    return partial(_lyapunov_map, theta=theta, rate=rate, exponent=exponent, threshold=threshold)


def _lyapunov_map(fig, theta, rate, exponent, threshold):
    ax = fig.add_subplot()
    image = ax.pcolormesh(np.degrees(theta), rate, exponent, shading="nearest", cmap="magma")
    ax.contour(np.degrees(theta), rate, exponent, [threshold], colors="cyan", linewidths=0.8)
    fig.colorbar(image, ax=ax, label="Lyapunov exponent [1/orbital period]")
    ax.set_xlabel("theta - f at periapsis [deg]")
    ax.set_ylabel("dtheta/dt / n at periapsis")
    ax.set_title(f"Hyperion-like, planar: chaotic (> {threshold:g}/T, cyan) vs regular")
