"""The edge: what meets the user and the references -- the command line and the Python API, scenario
files and the typed parameters they load into, the one runner, run directories and reports, sweeps,
the up-front budget, provenance.  It may import every layer below it and the astronomy libraries
(astropy, ERFA, skyfield, matplotlib, Dask); nothing below imports it (tests/test_layers.py)."""
