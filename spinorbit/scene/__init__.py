"""What a scene is written in, below the scenes: its declaration (``declaration.Scene``), its typed
parameters (``params``) and what a key may hold (``schema``), its verdict, the columns of its table and
its result.  Scenes, their comparisons and starts, and the solution store import it; it imports nothing
of theirs (tests/test_layers.py)."""
