"""Fixed internal units and physical constants (layer 0: numpy only).

Internal units: time in TDB days from J2000.0 (JD 2451545.0 TDB), lengths in km,
angles in radians, angular rates in rad/day, GM in km^3/day^2.  Moments of
inertia may be in any unit (only ratios enter the torque-driven dynamics).
"""
import math

J2000_JD = 2451545.0          # JD of J2000.0, TDB
DAY_S = 86400.0               # s per day
JULIAN_CENTURY_D = 36525.0    # days per Julian century
JULIAN_YEAR_D = 365.25

ARCSEC = math.pi / (180.0 * 3600.0)   # rad per arcsecond
MAS = ARCSEC / 1000.0                 # rad per milliarcsecond

# GM from DE421 (Folkner, Williams & Boggs 2008, IOM 343R-08-003), km^3/s^2.
_GM_KM3_S2 = {
    "sun": 132712440040.944,
    "earth": 398600.436233,
    "moon": 4902.800076,
    "venus": 324858.592,
    "jupiter": 126712764.800,   # Jupiter system barycentre
    "mars": 42828.375214,
    "saturn": 37940585.200,
    "mercury": 22032.090,
}
GM_KM3_D2 = {name: gm * DAY_S**2 for name, gm in _GM_KM3_S2.items()}
