"""Fixed internal units and physical constants (layer 0: numpy only).

Internal units: time in TDB days from J2000.0 (JD 2451545.0 TDB), lengths in km,
angles in radians, angular rates in rad/day, GM in km^3/day^2 (spinorbit.bodies.table).  Moments of
inertia may be in any unit (only ratios enter the torque-driven dynamics).
"""
import math

J2000_JD = 2451545.0          # JD of J2000.0, TDB
DAY_S = 86400.0               # s per day
JULIAN_CENTURY_D = 36525.0    # days per Julian century
JULIAN_YEAR_D = 365.25

ARCSEC = math.pi / (180.0 * 3600.0)   # rad per arcsecond
MAS = ARCSEC / 1000.0                 # rad per milliarcsecond
