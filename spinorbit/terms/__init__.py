"""Interactions as composable terms (layer 2): a model is a body plus a list of term names.

Each module here is one interaction, with its equation cited, building a :class:`base.Term`
from a :class:`base.Context`; :func:`build` makes the named ones and :func:`base.fuse` sums
them in one compiled kernel.  Adding a term is adding a module and a line to ``TERMS``: no
scene and no kernel is edited.
"""
from importlib import import_module

from .base import Context, Term, fuse  # noqa: F401  (the package's interface)

TERMS = {
    "point_mass": "spinorbit.terms.point_mass",        # Euler ch. 16 P91, §815/§818: degree 2, every mass
    "harmonics": "spinorbit.terms.harmonics",          # the figure's degree 3..4 field, every mass
    "earth_j2": "spinorbit.terms.figure_figure",       # the Earth's J2 on the degree-2 figure
    "sun_j2": "spinorbit.terms.sun_j2",                # the Sun's J2 on the degree-2 figure
}


def build(names, context):
    """Terms (base.Term) named in ``names``, built against ``context``; ValueError for an unknown name."""
    unknown = [name for name in names if name not in TERMS]
    if unknown:
        raise ValueError(f"unknown term {unknown[0]!r}; known terms: {sorted(TERMS)}")
    return tuple(import_module(TERMS[name]).build(context) for name in names)
