"""A scene's figures, one module a family of scenes (edge: matplotlib is imported by the caller of ``draw``).

Each function returns ``draw(fig)``, a ``functools.partial`` of a module-level function and its data (so
that it pickles: reports.Painter sends it to the process that draws); ``common.titled`` gives it the title
written above it, and a ``figsize`` attribute, when present, sizes the figure.  ``common`` holds the shared
drawing (curves, stacked panels, thinning, log labels); a scene imports the family module it draws.
"""
