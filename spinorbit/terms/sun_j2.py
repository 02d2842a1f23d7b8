"""The Sun's J2 on the degree-2 figure: the figure-figure term with the Sun as the oblate attractor.

The Sun's oblateness J2 = 2e-7 at R = 696000 km (the DE421 header's J2SUN and ASUN) and its
pole fixed in the ICRF at the IAU WGCCRE direction (spinorbit.bodies.sun); the torque is
Folkner et al.'s figure-figure form (terms.figure_figure).  Its size on the Moon, relative
to the Sun's point-mass torque, is of order J2 (R/r)^2 ~ 4e-12.
"""
import numpy as np

from ..bodies import sun
from . import figure_figure


def build(context):
    """The Sun's J2 on the figure; the Sun must be among the orbit's bodies."""
    gm = context.gm[context.index("sun", "sun_j2")]
    pole = np.array([[*sun.POLE_ICRF], [*sun.POLE_ICRF]])
    return figure_figure.oblate_attractor("sun", context, gm * sun.J2 * sun.RADIUS_KM ** 2,
                                          (np.array([0.0, 1.0]), pole), "sun_j2")
