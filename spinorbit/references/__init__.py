"""Independent references the runs are checked against (edge modules: may import astropy).

* ``moon_de421`` — the JPL DE421 lunar orientation (NAIF PCK via skyfield, and the
  ``de421`` package's libration arrays) and the DE421 lunar constants;
* ``erfa_pole`` — the IAU 2006/2000A celestial intermediate pole (ERFA).
"""
