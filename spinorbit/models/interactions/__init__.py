"""Interactions between the bodies of a System, one module each: what acts, with its reaction.

==================  ===========================================================================
``point_mass``      point masses on a degree-2 figure (Euler ch. 16 P91, §815, §818)
``harmonics``       point masses on a figure's field beyond degree 2 (Folkner et al. 2014)
``figure_figure``   an oblate body's J2 on a degree-2 figure, with the reaction on its own figure
``tides``           tides raised on the Earth by the Moon and the Sun, on the orbit and the spin (DE421)
``newton``          the point masses' attraction on a pair in the state
``relativity``      the EIH 1/c^2 point-mass correction
``geodesic``        de Sitter's precession of a spin frame
==================  ===========================================================================

Adding one: a module with its compiled kernels and an Interaction class that writes their calls
(spinorbit.models.interactions.base), then one line in an assembly (spinorbit.models.assemblies).
"""
from .figure_figure import FigureFigure, PoleTable
from .geodesic import Geodesic, GeodesicRate
from .harmonics import Harmonics
from .newton import Newton
from .point_mass import PointMass
from .relativity import Relativity
from .rings import Rings
from .tides import Tides

__all__ = ["FigureFigure", "PoleTable", "Geodesic", "GeodesicRate", "Harmonics", "Newton", "PointMass",
           "Relativity", "Rings", "Tides"]
