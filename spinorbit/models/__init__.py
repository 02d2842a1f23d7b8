"""Models as data: a System of bodies (figure, rotator), how they move, and what acts between them.

From that data a System derives its state layout, its parameter record and its compiled right-hand side
(spinorbit.models.system); the assemblies (spinorbit.models.assemblies) write every model the scenes use.
"""
from ..layout import Layout
from .barycentric import Barycentric
from .figure import Body, Field, Figure
from .motion import Centred, Pair
from .rotators import Distortion, Fixed, Gyroscopic, MantleCore, Rigid
from .system import System

__all__ = ["Barycentric", "Body", "Centred", "Distortion", "Field", "Figure", "Fixed", "Gyroscopic", "Layout",
           "MantleCore", "Pair", "Rigid", "System"]
