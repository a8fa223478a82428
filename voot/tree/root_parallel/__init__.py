r"""Root-parallel tree search: K independent trees on K workers, merged at the root.

Root parallelisation (Chaslot, Winands and van den Herik, 2008) runs :math:`K` searches
of the same root state with different seeds, with no communication between them, and
combines them only at the end, at the root. It needs no locks and no shared tree, so the
trees can run in separate processes (or on separate machines: the executor is a plug-in),
and the result of :math:`K` trees is a deterministic function of the base seed.

**Seeds.** Tree :math:`k` is seeded with ``np.random.SeedSequence(seed).spawn(K)[k]``,
whose spawn key is ``(k,)`` whatever :math:`K` is: tree :math:`k` is the same tree in a
run of 2 trees as in a run of 4, so adding trees only adds trees (:func:`tree_seeds`).

**Merging the root.** Every tree reports its root's edges (actions, :math:`\hat Q`, visit
counts, feasibility). Candidates are the feasible root edges of all trees (all edges if
none is feasible, as :meth:`voot.tree.Node.best_edge` does); the merged root action is a
candidate's own action, so it has been executed and its child is known. Rules
(:class:`MergeRule`):

``max_q``
    The candidate with the highest :math:`\hat Q` (ties: the lowest tree, then edge).
``most_visited``
    The candidate with the most visits (ties: higher :math:`\hat Q`, then lowest tree and
    edge). Both rules equal the single tree's ``final_action`` when :math:`K = 1`.
``vote``
    Actions of different trees never coincide in a continuous space, so "the same
    action" is replaced by "a nearby action": with :math:`z = (u - l) / (h - l)` the
    action in the root's box :math:`[l, h]` normalised to :math:`[0, 1]^d`, and
    :math:`\delta(u, u') = \lVert z - z' \rVert_2 / \sqrt d` (the root-mean-square
    coordinate difference in box widths, in :math:`[0, 1]` whatever :math:`d`), each
    candidate :math:`c` scores the visits of all candidates within ``vote_radius``
    :math:`r` of it (itself and the other trees' actions included):

    .. math:: V(c) = \sum_{c' :\ \delta(c, c') \le r} n(c').

    The candidate with the largest :math:`V` wins (ties: higher own :math:`\hat Q`, then
    lowest tree and edge). It is a kernel vote: a region that several trees explored
    heavily beats a single lucky action. Visits are summed, not values: :math:`\hat Q` can
    be negative (the infeasible penalty, distance costs), and a sum of values would count
    how many actions were tried near :math:`c` rather than how good they are; the
    decision reports the neighbourhood's best and visit-weighted mean :math:`\hat Q`.
    ``vote_radius = 0`` reduces the vote to ``most_visited`` summed over exact duplicates.

**The merged plan and curve.** The best plan is the best tree's (highest best return;
ties: lowest tree). The merged best-return curve is the maximum over trees at each
simulation index :math:`i`,

.. math:: B_K(i) = \max_{k < K} B^{(k)}(i), \qquad i = 1, \dots, N,

the best return known after every tree has run :math:`i` simulations: after :math:`i`
rounds of wall-clock time when the :math:`K` trees run in parallel. Plotted against the
*total* number of simulations :math:`K i`
(:meth:`RootParallelResult.curve_by_total_simulations`) it compares with one tree of
:math:`K N` simulations at equal computation; plotted against :math:`i` it compares at
(ideally) equal wall time.

**Workers.** The trees run on an executor of :mod:`voot.parallel`, the layer that runs
the benchmark sweeps too: a :class:`SerialExecutor` (in-process, for tests and for a sweep
that is already parallel), a :class:`LocalProcessExecutor` (a
:class:`~voot.parallel.ProcessExecutor`, the default), ``voot.bench``'s Ray backend, a
:class:`concurrent.futures.Executor` of your own, or any object with ``map(fn, items)``
(or only ``map_unordered(fn, items)``; results may come back in any order: each carries
its tree index and the merge sorts them). The work item (:class:`TreeTask`) and the
worker function (:func:`run_tree`) pickle, so they go to another process or machine as
they are. MuJoCo problems may not pickle (or not cheaply): pass a zero-argument
*factory* instead of the problem; each worker process builds the problem once per
factory and keeps it in its worker cache (:mod:`voot.parallel.cache`,
:func:`clear_problem_cache`), restoring its initial snapshot before every tree.

**Modules.** :mod:`~voot.tree.root_parallel.config` (options, merge rules, seeds),
:mod:`~voot.tree.root_parallel.merge` (root statistics and the merge),
:mod:`~voot.tree.root_parallel.worker` (one tree: task, worker function, result),
:mod:`~voot.tree.root_parallel.result` (the merged result) and
:mod:`~voot.tree.root_parallel.api` (:func:`plan_root_parallel`). Every name is
importable from ``voot.tree.root_parallel`` itself.
"""

from voot.parallel import Executor, ProcessExecutor
from voot.tree.root_parallel.api import (
    EXECUTORS,
    LocalProcessExecutor,
    SerialExecutor,
    TreeExecutor,
    plan_root_parallel,
)
from voot.tree.root_parallel.config import (
    MergeRule,
    RootParallelConfig,
    merge_rule,
    tree_seeds,
)
from voot.tree.root_parallel.merge import (
    MergeDecision,
    RootStats,
    merge_roots,
    normalized_distances,
)
from voot.tree.root_parallel.result import RootParallelResult, merge_trees
from voot.tree.root_parallel.worker import (
    PROBLEM_CACHE_SIZE,
    ProblemFactory,
    TreeResult,
    TreeTask,
    clear_problem_cache,
    prebuild_problem,
    run_tree,
)

__all__ = [
    "EXECUTORS",
    "PROBLEM_CACHE_SIZE",
    "Executor",
    "LocalProcessExecutor",
    "MergeDecision",
    "MergeRule",
    "ProblemFactory",
    "ProcessExecutor",
    "RootParallelConfig",
    "RootParallelResult",
    "RootStats",
    "SerialExecutor",
    "TreeExecutor",
    "TreeResult",
    "TreeTask",
    "clear_problem_cache",
    "merge_roots",
    "merge_rule",
    "merge_trees",
    "normalized_distances",
    "plan_root_parallel",
    "prebuild_problem",
    "run_tree",
    "tree_seeds",
]
