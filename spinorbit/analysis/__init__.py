"""Analysis of integrated runs: what a span can fit (``spans``), and the fits, ladders and exponents
built on it.  Layer 2 (numpy, scipy): every scene asks this package, none carries its own."""
