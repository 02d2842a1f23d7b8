"""The Sun: its oblateness and pole.

J2 = 2e-7 at the reference radius 696000 km: the DE421 header's J2SUN and ASUN.
Pole: IAU WGCCRE (Archinal et al. 2018, CMDA 130:22), right ascension 286.13 deg and
declination 63.87 deg (ICRF, J2000), constant.
Rotation, for a Sun that turns (a closed system's; the ephemerides hold its figure fixed): C/(M R^2) = 0.070 and
the sidereal period 25.38 d (NASA NSSDCA Sun Fact Sheet), taken at J2's radius.
"""
import math

import numpy as np

J2 = 2.0e-7                         # DE421 header J2SUN
RADIUS_KM = 696000.0                # DE421 header ASUN, J2's reference radius
POLE_RA_DEG, POLE_DEC_DEG = 286.13, 63.87
C_MR2 = 0.070                       # NASA Sun Fact Sheet, moment of inertia I/(M R^2)
SIDEREAL_ROTATION_D = 25.38         # Carrington's sidereal period
POLE_ICRF = np.array([math.cos(math.radians(POLE_DEC_DEG)) * math.cos(math.radians(POLE_RA_DEG)),
                      math.cos(math.radians(POLE_DEC_DEG)) * math.sin(math.radians(POLE_RA_DEG)),
                      math.sin(math.radians(POLE_DEC_DEG))])
