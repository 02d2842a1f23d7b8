"""The model starts several modules share (a scene and its comparison, another start, the solution store): a
System and its initial state where building them needs an edge module (astropy, ERFA or spinorbit.references).
A start with one user lives in that user, unless the user is a scene module (a declaration): then it stays here.
Builders that need no edge module live in spinorbit.models."""
