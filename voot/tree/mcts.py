r"""Monte Carlo tree search with an action optimiser at every node (paper Algorithms 1-2).

One *simulation* (Algorithm 2, written as a loop instead of a recursion) starts at the
current root and, at every node :math:`s` reached at relative depth :math:`h`:

1. picks an action :math:`u` by the configured selection rule (for VOOT: re-evaluate the
   newest action while it has fewer than :math:`1 + w\,\kappa_r^h` evaluations, else ask
   the node's optimiser for a new action, fed with the node's :math:`\hat Q`);
2. a *new* action is proposed until it passes the problem's feasibility check (at most
   ``feasibility_retries`` proposals; if all fail, the last is executed) and executed
   with ``problem.step``; the resulting child is created with its snapshot;
   an *existing* action is followed along its edge: the problem is deterministic, so the
   child is already known and nothing is simulated (design.md's "main speed lever");
3. stops at an infeasible action, a terminal state or the depth limit :math:`H`.

The return is then backed up from the end of the path to the *original* root (also
through the nodes the root was committed past):
:math:`G = r + b + \gamma\,G_{\text{child}}`, with :math:`b` the goal bonus, and
:math:`\hat Q(s, u)` absorbs :math:`G` by the backup rule (paper: the maximum).

After every simulation the search records the best discounted sum of rewards (goal bonus
excluded) over the paths from the original root: the paper's curve.

Size: one concept, the search (its loop, new actions, backup, commitment, result); the
selection rules live in :mod:`voot.tree.selection`.
"""

from __future__ import annotations

import gc
import heapq
import math
from collections.abc import Callable, Mapping
from dataclasses import replace
from typing import Any

import numpy as np

from voot import validation as V
from voot.optim.base import FloatArray
from voot.tree.config import (
    Backup,
    BestReturnOver,
    CommitReset,
    FinalAction,
    MCTSConfig,
    planner_config,
)
from voot.tree.hoo import HOO, HOOConfig
from voot.tree.node import Node
from voot.tree.problem import PlanningProblem, check_problem, problem_bounds, step_values
from voot.tree.samplers import UniformSampler, make_optimizer_sampler, same_point
from voot.tree.search import PlanResult, Search
from voot.tree.selection import SelectionRule, make_selection

#: ``callback(mcts, simulation_index)`` after every simulation; return True to stop early.
Callback = Callable[["MCTS", int], Any]

#: Without a depth limit a rollout must end at an infeasible action or a terminal state;
#: one longer than this is taken for a problem that never ends and stops with an error.
MAX_UNLIMITED_DEPTH = 10_000


class MCTS(Search):
    """The tree search over a :class:`~voot.tree.problem.PlanningProblem`.

    Args:
        problem: the world; its current state is the root.
        config: a :class:`MCTSConfig` (default: VOOT), or a planner name (``"voot"``).
        seed: seed of the one generator every node's sampler draws from.

    ``search(n)`` runs ``n`` more simulations and returns a :class:`PlanResult`; call it
    again to continue the same tree. The tree is open for inspection: :attr:`root`,
    :attr:`nodes`, :attr:`current_root` (after root commitments).
    """

    def __init__(
        self,
        problem: PlanningProblem,
        config: MCTSConfig | str | None = None,
        seed: int | np.random.SeedSequence | None = None,
    ) -> None:
        if isinstance(config, str):
            config = planner_config(config)
        cfg = config if config is not None else MCTSConfig()
        if not isinstance(cfg, MCTSConfig):
            raise TypeError(
                f"config must be an MCTSConfig or a planner name, got {type(cfg).__name__}"
            )
        check_problem(problem)
        self.problem = problem
        self.config = cfg
        self.rng = np.random.default_rng(V.seed(seed))
        # A problem may offer is_feasible (FeasibilityCheck) or set it to None per instance.
        check = getattr(problem, "is_feasible", None)
        self._check: Callable[[FloatArray], bool] | None = check if callable(check) else None
        self._sampler_config = cfg.sampler_config()
        # The problem's per-state distance (ActionMetric), if asked for and usable.
        metric = getattr(problem, "action_metric", None)
        self._metric: Callable[[], Any] | None = (
            metric
            if cfg.use_problem_metric
            and callable(metric)
            and hasattr(self._sampler_config, "metric")
            else None
        )
        self._metric_configs: dict[Any, Any] = {}
        self._optimizer_class: Any = None
        if cfg.sampler not in ("uniform", "hoo"):
            from voot.optim.registry import optimizer_class

            self._optimizer_class = optimizer_class(cfg.sampler)
        self._rule: SelectionRule = make_selection(cfg)
        self._backup = Backup(cfg.backup)
        self._gamma = float(cfg.gamma)
        self._H = cfg.depth_limit
        root_bounds = problem_bounds(problem)
        self._init_tree(Node(0, None, -1, 0, 1.0, 0.0, problem.snapshot()))
        self.root.bounds = root_bounds
        self.n_steps = 0
        self.n_feasibility_checks = 0

    def _init_tree(self, root: Node) -> None:
        self.root = root
        #: Every node, in creation order (``nodes[i].id == i``).
        self.nodes: list[Node] = [root]
        #: The root of the next simulation (moves down with root commitment).
        self.current_root = root
        self._prefix: list[tuple[Node, int]] = []
        self._at: Node | None = None
        self._commit_threshold = self.config.root_commitment
        self._goal_found = False
        self._leaves: list[tuple[float, int]] = [(-root.path_return, root.id)]
        self._best_node = root
        self._has_complete = False
        self.n_node_visits = 0
        self._start_curve()

    # ----- public --------------------------------------------------------------------------
    def search(
        self,
        n_simulations: int,
        callback: Callback | None = None,
        record_info: str | None = None,
    ) -> PlanResult:
        """:meth:`Search.search <voot.tree.search.Search.search>` on this tree (``callback``
        gets the MCTS; ``record_info`` is read at the best leaf)."""
        self._at = None  # the caller may have moved the problem between searches
        # The tree only grows during a search, so Python's cyclic garbage collector would
        # only re-traverse it (about 15% of the search's time): pause it meanwhile.
        gc_was_enabled = gc.isenabled()
        gc.disable()
        try:
            return super().search(n_simulations, callback, record_info)
        finally:
            if gc_was_enabled:
                gc.enable()

    def _best_info(self) -> Mapping[str, Any]:
        return self.best_node().info

    def _root_snapshot(self) -> Any:
        return self.root.snapshot

    def best_node(self) -> Node:
        """The end of the best path from the root (see ``best_return_over``).

        With ``complete`` and no complete path yet, the root (an empty plan).
        """
        if self.config.best_return_over is not BestReturnOver.LEAVES:
            return self._best_node
        heap, nodes = self._leaves, self.nodes
        while nodes[heap[0][1]].children:
            heapq.heappop(heap)
        return nodes[heap[0][1]]

    @property
    def best_return(self) -> float:
        """Best discounted return (goal bonus excluded) over paths from the root.

        ``-inf`` with ``best_return_over="complete"`` until a path is complete.
        """
        if self.config.best_return_over is BestReturnOver.COMPLETE and not self._has_complete:
            return -math.inf
        return self.best_node().path_return

    @property
    def commit_threshold(self) -> int | None:
        """Counted actions the current root needs before the next commitment check.

        Starts at ``root_commitment`` (None: commitment off) and doubles each time a
        check keeps the root where it is (a terminal child) or, with
        ``commit_reset_on_goal``, returns it to the original root after a goal.
        """
        return self._commit_threshold

    def best_plan(self) -> list[tuple[Node, int]]:
        """``(node, edge)`` pairs of the best path from the root."""
        return self.best_node().path()

    def recommended_edge(self) -> int:
        """The root edge chosen by ``final_action`` (-1 if the root has no action)."""
        if self.config.final_action is FinalAction.MOST_VISITED:
            return self.root.most_visited_edge()
        return self.root.best_edge()

    def result(self, with_info_curve: bool = False) -> PlanResult:
        """The :class:`PlanResult` of the tree as it is now."""
        path = self.best_plan()
        best = self.best_node()
        i = self.recommended_edge()
        return PlanResult(
            actions=tuple(node.actions[e].copy() for node, e in path),
            rewards=np.array([node.rewards[e] for node, e in path], dtype=np.float64),
            bonuses=np.array([node.bonuses[e] for node, e in path], dtype=np.float64),
            feasible=tuple(bool(node.feasible[e]) for node, e in path),
            best_return=float(self.best_return),
            best_return_curve=np.array(self.best_return_curve, dtype=np.float64),
            info_curve=tuple(self.info_curve) if with_info_curve else None,
            best_action=None if i < 0 else self.root.actions[i].copy(),
            best_leaf_info=best.info,
            n_simulations=self.n_simulations,
            n_nodes=len(self.nodes),
            n_steps=self.n_steps,
            n_feasibility_checks=self.n_feasibility_checks,
            n_node_visits=self.n_node_visits,
            wall_time=self.wall_time,
            mcts=self,
        )

    def reroot(self, edge: int) -> Node:
        """Keep only the subtree below the root's ``edge`` (subtree reuse after executing it).

        Depths, discounts and path returns are recomputed relative to the new root; the
        curve and counters restart. Returns the new root.
        """
        if not 0 <= edge < len(self.root.children):
            raise IndexError(
                f"edge {edge} out of range for a root with {len(self.root.children)} actions"
            )
        new_root = self.root.children[edge]
        if not new_root.expandable:
            raise ValueError("cannot re-root at a terminal or infeasible state")
        new_root.parent, new_root.edge = None, -1
        new_root.depth, new_root.discount, new_root.path_return = 0, 1.0, 0.0
        new_root.info = {}
        nodes: list[Node] = []
        gamma = self._gamma
        for node in new_root.subtree():
            node.id = len(nodes)
            nodes.append(node)
            for e, child in enumerate(node.children):
                child.depth = node.depth + 1
                child.discount = node.discount * gamma
                child.path_return = node.path_return + node.discount * node.rewards[e]
        n_steps, n_checks = self.n_steps, self.n_feasibility_checks
        self._init_tree(new_root)
        self.nodes = nodes
        self._leaves = [(-n.path_return, n.id) for n in nodes if not n.children]
        heapq.heapify(self._leaves)
        mode = self.config.best_return_over
        candidates = (
            [n for n in nodes if self._is_complete(n)] if mode is BestReturnOver.COMPLETE else nodes
        )
        self._has_complete = mode is BestReturnOver.COMPLETE and bool(candidates)
        self._best_node = max(candidates, key=lambda n: n.path_return) if candidates else new_root
        self.n_steps, self.n_feasibility_checks = n_steps, n_checks
        return new_root

    # ----- one simulation --------------------------------------------------------------------
    def _simulate(self) -> None:
        self._maybe_commit()
        H = self._H
        node = self.current_root
        path_nodes: list[Node] = []
        path_edges: list[int] = []
        depth = 0
        select = self._rule.select
        limit = MAX_UNLIMITED_DEPTH if H is None else H
        while not (node.terminal or node.infeasible) and depth < limit:
            i = select(self, node, depth)
            path_nodes.append(node)
            path_edges.append(i)
            node = node.children[i]
            depth += 1
        if H is None and depth >= limit and not (node.terminal or node.infeasible):
            raise RuntimeError(
                f"a rollout reached depth {depth} without a terminal state or an infeasible"
                " action; set depth_limit (the horizon H) for problems that do not end"
            )
        self.n_node_visits += depth
        if self._prefix:
            path_nodes = [p for p, _ in self._prefix] + path_nodes
            path_edges = [e for _, e in self._prefix] + path_edges
        self._backup_path(path_nodes, path_edges)

    def _backup_path(self, path_nodes: list[Node], path_edges: list[int]) -> None:
        gamma = self._gamma
        rule = self._backup
        is_max = rule is Backup.MAX
        is_jump = rule is Backup.JUMP_MAX_ELSE_MEAN
        observe = self._rule.observe
        tell = self._rule.tells_sampler
        v = 0.0
        for j in range(len(path_nodes) - 1, -1, -1):
            node = path_nodes[j]
            i = path_edges[j]
            ret = node.rewards[i] + node.bonuses[i] + gamma * v
            c = node.n[i] + 1
            node.n[i] = c
            node.visits += 1
            q = node.q[i]
            sampler = node.sampler
            observe(node, i, ret)
            if c == 1:
                node.q[i] = ret
                if tell and sampler is not None:
                    sampler.add(node.actions[i], ret, node.feasible[i])
                v = ret
                continue
            if is_max:
                if ret > q:
                    node.q[i] = ret
                    if tell:
                        sampler.update(i, ret)
                    v = ret
                else:
                    v = q
                continue
            if is_jump and ret > q:
                new = ret
            else:
                new = q + (ret - q) / c
            if new != q:
                node.q[i] = new
                if tell:
                    sampler.update(i, new)
            v = ret

    # ----- new actions (what the selection rules call) ---------------------------------------
    def goto(self, node: Node) -> None:
        """Put the problem in ``node``'s state (a restore unless it is there already)."""
        if self._at is not node:
            self.problem.restore(node.snapshot)
            self._at = node

    def sampler(self, node: Node) -> Any:
        """The node's sampler, created on its first new action (the problem is at ``node``)."""
        if node.sampler is None:
            if node.bounds is None:
                node.bounds = problem_bounds(self.problem)
            cfg = self.config
            if cfg.sampler == "uniform":
                node.sampler = UniformSampler(node.bounds, self.rng)
            elif cfg.sampler == "hoo":
                hoo_cfg = self._sampler_config
                assert isinstance(hoo_cfg, HOOConfig)
                node.sampler = HOO(node.bounds, hoo_cfg, self.rng)
            else:
                node.sampler = make_optimizer_sampler(
                    self._optimizer_class,
                    self._node_sampler_config(),
                    node.bounds,
                    self.rng,
                    cfg.voo_uniform_until_feasible and cfg.sampler == "voo",
                )
        return node.sampler

    def _node_sampler_config(self) -> Any:
        """The sampler config for the problem's current state (its metric, if used)."""
        if self._metric is None:
            return self._sampler_config
        metric = self._metric()
        if metric is None:
            return self._sampler_config
        config = self._metric_configs.get(metric)
        if config is None:
            config = replace(self._sampler_config, metric=metric)
            self._metric_configs[metric] = config
        return config

    def new_action(self, node: Node) -> int:
        """Draw a new action from ``node``'s sampler, pre-check it, execute it: its edge."""
        self.goto(node)
        sampler = self.sampler(node)

        def redraw(previous: FloatArray) -> FloatArray | None:
            sampler.reject(previous)
            x: FloatArray = sampler.propose()
            # a deterministic sampler repeats itself: no new draw to check
            return None if same_point(previous, x) else x

        return self.add_action(node, sampler.propose(), redraw)

    def add_action(
        self, node: Node, x: FloatArray, redraw: Callable[[FloatArray], FloatArray | None]
    ) -> int:
        """The two stages of a new action at ``node`` (the problem is there): its edge.

        Stage 1: while ``x`` fails the problem's pre-check, ``redraw(x)`` gives the next
        draw (None: nothing new to draw), at most ``feasibility_retries`` draws in all;
        stage 2: the last draw is executed (:meth:`_execute`), feasible or not.
        """
        check = self._check
        if check is not None:
            retries = self.config.feasibility_retries
            for t in range(retries):
                self.n_feasibility_checks += 1
                if check(x) or t == retries - 1:
                    break
                following = redraw(x)
                if following is None:
                    break
                x = following
        return self._execute(node, x)

    def _execute(self, node: Node, x: FloatArray) -> int:
        """Step the problem (which is at ``node``) with ``x``; add the edge and its child."""
        res = self.problem.step(x)
        self.n_steps += 1
        self._at = None  # the problem has moved; the child records where, once made
        reward, bonus = step_values(self.problem, x, res)
        feasible = bool(res.feasible)
        terminal = bool(res.terminal)
        expandable = feasible and not terminal
        child = Node(
            len(self.nodes),
            node,
            len(node.actions),
            node.depth + 1,
            node.discount * self._gamma,
            node.path_return + node.discount * reward,
            self.problem.snapshot() if expandable else None,
            terminal,
            not feasible,
            res.info,
        )
        self._at = child
        self.nodes.append(child)
        node.actions.append(x)
        node.rewards.append(reward)
        node.bonuses.append(bonus)
        node.feasible.append(feasible)
        node.children.append(child)
        node.q.append(-math.inf)
        node.n.append(0)
        if feasible:
            node.n_feasible += 1
            low = self.config.commit_min_reward
            if low is None or reward >= low:
                node.n_commit_actions += 1
        if terminal:
            node.n_terminal_children += 1
            if feasible:
                self._goal_found = True
        mode = self.config.best_return_over
        if mode is BestReturnOver.LEAVES:
            heapq.heappush(self._leaves, (-child.path_return, child.id))
        elif mode is BestReturnOver.NODES:
            if child.path_return > self._best_node.path_return:
                self._best_node = child
        elif self._is_complete(child) and (
            not self._has_complete or child.path_return > self._best_node.path_return
        ):
            self._best_node = child
            self._has_complete = True
        return len(node.actions) - 1

    def _is_complete(self, node: Node) -> bool:
        """Whether the path to ``node`` is finished: terminal, infeasible or at depth H."""
        H = self._H
        return node.terminal or node.infeasible or (H is not None and node.depth >= H)

    # ----- root commitment -----------------------------------------------------------------
    def _maybe_commit(self) -> None:
        """Move the root to its best feasible child once it has enough counted actions.

        With ``commit_reset_on_goal``, once a goal leaf exists the root goes back to the
        original root instead (and the threshold doubles), so that the search improves
        the whole plan rather than only its tail; with ``commit_reset_trigger=
        "root_goal_child"`` (the authors' code) only a goal child of the current root
        sends it back.
        """
        threshold = self._commit_threshold
        root = self.current_root
        if threshold is None or root.n_commit_actions < threshold:
            return
        cfg = self.config
        if cfg.commit_reset_on_goal and (
            root.n_terminal_children
            if cfg.commit_reset_trigger is CommitReset.ROOT_GOAL_CHILD
            else self._goal_found
        ):
            self._commit_threshold = 2 * threshold
            self._prefix.clear()
            self.current_root = self.root
            return
        if root.n_terminal_children:  # the original: stay, and ask for more next time
            self._commit_threshold = 2 * threshold
            return
        best, best_q = -1, -math.inf
        for i, child in enumerate(root.children):
            if root.feasible[i] and child.expandable and (best < 0 or root.q[i] > best_q):
                best, best_q = i, root.q[i]
        if best < 0 or (self._H is not None and self._H <= 1):
            return
        self._prefix.append((root, best))
        self.current_root = root.children[best]
