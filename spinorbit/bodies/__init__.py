"""Bodies (layer 1): one module per body holding its mass, figure, core, tides and rotation
constants, each with its source and its unit in its name.  ``rigid`` is the generic triaxial
body (principal moments and axes); ``moon``, ``earth``, ``sun`` the real ones, read from the
DE421 header (``de421``) where it has them, else from the IAU and the papers cited.
"""
from .rigid import RigidBody

__all__ = ["RigidBody"]
