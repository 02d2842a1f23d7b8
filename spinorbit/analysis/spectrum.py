"""The amplitude spectrum of a sampled series.  Layer 2 (numpy)."""
import numpy as np


def amplitude_spectrum(t, x):
    """(period, amplitude) of x(t), period in the unit of t: Hann-windowed, 4x zero-padded FFT of the
    detrended series on a uniform grid; a sinusoid of amplitude a shows a peak of height ~a at its period."""
    order = np.argsort(t)                                   # a backward run's times descend
    t, x = np.asarray(t)[order], np.asarray(x)[order]
    grid = np.linspace(t[0], t[-1], t.size)
    y = np.interp(grid, t, x)
    y = y - np.polyval(np.polyfit(grid, y, 1), grid)
    window = np.hanning(y.size)
    n = 4 * y.size
    amplitude = 2 * np.abs(np.fft.rfft(y * window, n)) / window.sum()
    frequency = np.fft.rfftfreq(n, grid[1] - grid[0])
    return 1 / frequency[1:], amplitude[1:]
