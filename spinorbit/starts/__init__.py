"""A scene's System and initial state where building them needs an edge module (astropy, ERFA or
spinorbit.references), one module per model: the scenes declare, these build; builders that need none live in
spinorbit.models."""
