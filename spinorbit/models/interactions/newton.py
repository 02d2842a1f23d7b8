"""The point masses' Newtonian attraction on a pair in the state (Euler ch. 16 P90, §813; the ephemerides' monopoles).

For the pair's relative orbit r (the secondary from the primary): the pair's own monopole exactly,
-(GM_p + GM_s) r / r^3, and every other mass's pull as the difference of its pulls on the two,
GM_j [(x_j - x_s)/|x_j - x_s|^3 - (x_j - x_p)/|x_j - x_p|^3].  Where every centre is in the state
(spinorbit.models.barycentric), every body's barycentric acceleration too, sum_j GM_j (x_j - x_i)/|x_j - x_i|^3
(spinorbit.models.interactions.relativity.newtonian), and the energy -sum_{i<j} GM_i GM_j / r_ij.
"""
from dataclasses import dataclass

import numpy as np

from ...base.linker import cached
from ...base.rotations import dot3
from .base import Interaction
from .relativity import newtonian


@cached(nogil=True)
def pair_acceleration(x, mu, r):
    """r'' (km/d^2) of the pair (rows n - 2: primary, n - 1: secondary of x (n, 3) km, mu (n,) km^3/d^2)."""
    n = x.shape[0]
    r2 = dot3(r, r)
    acc = -(mu[n - 2] + mu[n - 1]) / (r2 * np.sqrt(r2)) * r
    for j in range(n - 2):
        to_s, to_p = x[j] - x[n - 1], x[j] - x[n - 2]
        ds, dp = dot3(to_s, to_s), dot3(to_p, to_p)
        acc += mu[j] * (to_s / (ds * np.sqrt(ds)) - to_p / (dp * np.sqrt(dp)))
    return acc


@cached(nogil=True)
def potential_energy(x, mu, r):
    """-sum_{i<j} GM_i GM_j / r_ij (G-scaled) of the masses at x (n, 3) km, the pair (the last two rows) at r."""
    n = x.shape[0]
    total = -mu[n - 2] * mu[n - 1] / np.sqrt(dot3(r, r))
    for i in range(n - 1):
        for j in range(i + 1, n if i < n - 2 else n - 1):      # the pair's own term from r
            d = x[j] - x[i]
            total -= mu[i] * mu[j] / np.sqrt(dot3(d, d))
    return total


@dataclass(frozen=True)
class Newton(Interaction):
    """Every point mass of the System (the orbit source's and the pair) attracting the pair in the state."""

    phase = "orbit"
    citation = "Newton; Euler, Theoria motus ch. 16 P90 (§813)"

    def bodies(self):
        return ()

    def emit(self, code):
        motion = code.system.motion
        x, _, mu = motion.point_masses(code)
        if motion.carries_centres:
            newton = code.local("newton")
            code.line(f"{newton} = {code.bind(newtonian)}({x}, {mu})[0]")
            motion.add_centre_accelerations(code, newton)
        r = motion.relative(code, motion.primary, motion.secondary)
        motion.add_relative_acceleration(code, f"{code.bind(pair_acceleration)}({x}, {mu}, {r})")

    def energy(self, code):
        motion = code.system.motion
        if not motion.closed:
            return super().energy(code)
        r = motion.relative(code, motion.primary, motion.secondary)
        if motion.carries_centres:
            x, _, mu = motion.point_masses(code)
            return f"{code.bind(potential_energy)}({x}, {mu}, {r})"
        product = motion.gm(motion.primary) * motion.gm(motion.secondary)
        return f"-{code.param('gm_product', product)} / np.sqrt({r}[0] * {r}[0] + {r}[1] * {r}[1] + {r}[2] * {r}[2])"
