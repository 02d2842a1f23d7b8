"""Right-hand sides of the models the scenes integrate, one module per model (layer 2)."""
