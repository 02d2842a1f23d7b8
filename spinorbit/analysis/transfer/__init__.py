"""Transfer functions of the non-rigid Earth: the ratio T(sigma) of a non-rigid to a rigid Earth's nutation.

Layer 2 (numpy).  A circular nutation of celestial frequency nu (cycles per sidereal day, cpsd; prograde > 0,
time dependence exp(+i nu Omega t) in the plane (dpsi sin eps, deps)) is a wobble of terrestrial frequency
sigma = nu - 1, and its amplitude ratio is T(sigma) (Mathews, Herring & Buffett 2002, JGR 107(B4) 2068;
IERS Conventions 2010, TN36 §5.5.1).

* ``forms`` -- the three forms: the resonance expansion, the two-layer Earth, a table with a resonance
  expansion between its frequencies (and the fit of one to the other);
* ``models`` -- the published models built from them (``MODELS``: MHB2000's own, the IERS 1996 factors,
  the two-layer Earth with MHB2000's parameters);
* ``mhb2000_table`` -- MHB2000's transfer function at the nutation frequencies, derived from data.
"""
