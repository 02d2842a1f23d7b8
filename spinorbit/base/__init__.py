"""Layer 0: what every layer stands on and nothing below it -- constants, errors, rotations, the state's
layout, progress on stderr, private folders, atomic files and the verified cache room, the version.

Imports nothing of spinorbit above it and no astronomy library (tests/test_layers.py)."""
