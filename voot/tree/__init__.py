"""Monte Carlo tree search with a pluggable action optimiser at every node (VOOT)."""
