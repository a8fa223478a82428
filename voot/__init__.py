"""voot: Voronoi Optimistic Optimization, VOOT tree search, and a MuJoCo benchmark suite.

Layers (each imports only those above it)::

    voot.optim      black-box maximisers with one ask/tell interface (VOO and baselines)
    voot.functions  test functions with bounds and known optima
    voot.tree       MCTS with a pluggable action optimiser per node (VOOT and baselines)
    voot.envs       MuJoCo scenes as gymnasium environments (needs the [envs] extra)
    voot.record     rerun recordings of searches and plans (needs the [record] extra)
    voot.bench      benchmark runner, result store, plots and the ``voot-bench`` CLI

Importing ``voot`` registers the gymnasium environment ids (``voot/...``) without
importing MuJoCo; the environments load it when made.
"""

from voot import _source_tree

_source_tree.install(__file__)  # first: the families' records live in voot.envs

from voot._registration import register_envs  # noqa: E402

__version__ = "0.1.0"

register_envs()

__all__ = ["__version__", "register_envs"]
