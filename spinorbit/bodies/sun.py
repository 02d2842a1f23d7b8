"""The Sun: its oblateness and pole.

J2 = 2e-7 at the reference radius 696000 km: the DE421 header's J2SUN and ASUN.
Pole: IAU WGCCRE (Archinal et al. 2018, CMDA 130:22), right ascension 286.13 deg and
declination 63.87 deg (ICRF, J2000), constant.
"""
import math

import numpy as np

J2 = 2.0e-7                         # DE421 header J2SUN
RADIUS_KM = 696000.0                # DE421 header ASUN, J2's reference radius
POLE_RA_DEG, POLE_DEC_DEG = 286.13, 63.87
POLE_ICRF = np.array([math.cos(math.radians(POLE_DEC_DEG)) * math.cos(math.radians(POLE_RA_DEG)),
                      math.cos(math.radians(POLE_DEC_DEG)) * math.sin(math.radians(POLE_RA_DEG)),
                      math.sin(math.radians(POLE_DEC_DEG))])
