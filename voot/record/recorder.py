"""Record a tree search into a rerun ``.rrd`` file through the search's callback.

Usage (any :class:`~voot.tree.PlanningProblem`)::

    from voot.record import SearchRecorder
    from voot.tree import MCTS

    mcts = MCTS(problem, "voot", seed=0)
    with SearchRecorder("run.rrd", problem) as recorder:
        result = mcts.search(1000, callback=recorder)
    # or: recorder = SearchRecorder(...); mcts.search(..., callback=recorder); recorder.finish()

or in one call: :func:`record_plan`. Open the file with ``rerun run.rrd``.

What is written (entity paths; timelines ``search`` = simulation index, ``plan`` = step
index of the best plan):

* ``search/best_return``, ``search/n_nodes``: scalars after every simulation;
* ``samples/<name>`` or ``scene/samples/<name>/{base_poses,placements}``: the watched
  nodes' sampled actions coloured by :math:`\\hat Q` (see :mod:`voot.record.samples`),
  every ``samples_every`` simulations and after the last;
* ``tree``: the search tree as a graph, at the end (or every ``tree_every`` simulations);
* ``plan/reward``, ``plan/return``, ``plan/action``, ``plan/info``: along the best plan;
* ``scene/bodies/...``: with a MuJoCo problem, the geometry (static) and the body poses
  at every state of the best plan, obtained by replaying the plan's actions from the
  root's snapshot (the problem is restored afterwards); the root's poses also sit at
  ``search`` index 0 so that the scene shows while scrubbing the search;
* ``scene/plan/{base_pose,placement}``: the executed action's pose at each plan step;
* a default blueprint (:func:`voot.record.blueprint.default_blueprint`), its 3-D view
  opening at the scene's ``perspective`` camera (``RecorderConfig.view_camera``).

Cost: scalars and sample drawings are buffered and sent as columns every
``flush_every`` simulations (a drawing grows with the node's action count; one is made
every ``samples_every`` simulations); the tree graph is logged once. See :mod:`voot.bench.measure.overhead` for measured figures.
"""

from __future__ import annotations

import math
import os
import uuid
import warnings
from collections.abc import Callable, Mapping
from pathlib import Path
from types import TracebackType
from typing import Any

import numpy as np

from voot.record.blueprint import (
    BEST_RETURN,
    N_NODES,
    PLAN,
    PLAN_TIMELINE,
    SAMPLES_2D,
    SCENE,
    SEARCH_TIMELINE,
    TREE,
    Eye3D,
    default_blueprint,
)
from voot.record.config import AUTO_CAMERA, BEST_PREFIX, PERSPECTIVE_CAMERA, ROOT, RecorderConfig
from voot.record.mujoco_scene import MujocoScene, camera_names, find_mujoco, model_camera_eye
from voot.record.samples import BASE_POSE_KEY, PLACEMENT_KEY, NodeSamples, SampleLog, pose_of
from voot.record.tree_graph import build_tree_graph, log_tree
from voot.tree.mcts import MCTS
from voot.tree.node import Node
from voot.tree.search import PlanResult

Callback = Callable[[MCTS, int], Any]


def combine_callbacks(*callbacks: Callback | None) -> Callback:
    """One search callback calling each of ``callbacks`` in turn (None entries skipped).

    The search stops when any of them returns True (all are still called).
    """
    cbs = [cb for cb in callbacks if cb is not None]

    def callback(mcts: MCTS, i: int) -> bool:
        stop = False
        for cb in cbs:
            stop = bool(cb(mcts, i)) or stop
        return stop

    return callback


def watch_name(entry: str | int) -> str:
    """Entity-path name of a watch entry: ``root``, ``node_<id>``, ``first_<operator>``,
    ``best_<operator>``."""
    if isinstance(entry, int):
        return f"node_{entry}"
    if entry == ROOT:
        return ROOT
    prefix = "first_"
    if entry.startswith(BEST_PREFIX):
        prefix, entry = "best_", entry[len(BEST_PREFIX) :]
    safe = "".join(c if c.isalnum() or c in "_-" else "_" for c in entry)
    return f"{prefix}{safe}"


def _info_text(
    step: int, action: Any, reward: float, bonus: float, feasible: bool, info: Mapping[str, Any]
) -> str:
    lines = [
        f"step {step}: reward {reward:.6g}" + (f" + bonus {bonus:.6g}" if bonus else ""),
        "feasible" if feasible else "INFEASIBLE",
        "action " + np.array2string(np.asarray(action), precision=4, max_line_width=200),
    ]
    for k, v in info.items():
        text = repr(v)
        lines.append(f"{k}: {text if len(text) <= 200 else text[:197] + '...'}")
    return "\n".join(lines)


class SearchRecorder:
    """A search callback that writes a rerun recording (see the module docstring).

    Args:
        path: the ``.rrd`` file to write (its folder is created).
        problem: the planning problem searched; default: the searched tree's
            ``mcts.problem`` (known from the first callback). Needed before the search
            only to log the scene geometry right away.
        config: a :class:`RecorderConfig`; ``**options`` override its fields.
        scene: where the MuJoCo model is: None finds it on the problem (its
            ``unwrapped.model``/``data``), False records no scene, or a ``(model, data)``
            pair / an object holding them (an env).
        recording_id: rerun recording id (default: a random UUID).
        blueprint: a ``rerun.blueprint.Blueprint`` to send instead of the default layout
            (:func:`voot.record.blueprint.default_blueprint`).

    The recorder is the callback: pass it as ``callback=recorder`` to
    :meth:`voot.tree.MCTS.search` or :func:`voot.tree.plan`, then call :meth:`finish`
    (or use it as a context manager). It never stops the search. The ``search``
    timeline counts the callbacks it received (the simulation index of one search; it
    keeps counting across several searches of one tree and across re-rooting, where the
    watched nodes are looked up again in the new tree).
    """

    def __init__(
        self,
        path: str | os.PathLike[str],
        problem: Any = None,
        config: RecorderConfig | None = None,
        *,
        scene: Any = None,
        recording_id: str | None = None,
        blueprint: Any = None,
        **options: Any,
    ) -> None:
        import rerun as rr

        cfg = config if config is not None else RecorderConfig()
        if not isinstance(cfg, RecorderConfig):
            raise ValueError(f"config must be a RecorderConfig, got {type(cfg).__name__}")
        if options:
            cfg = cfg.replace(**options)
        self.config = cfg
        self.path = Path(path)
        if self.path.suffix != ".rrd":
            raise ValueError(f"a rerun recording file must end in .rrd, got {str(path)!r}")
        self.path.parent.mkdir(parents=True, exist_ok=True)
        self.rec = rr.RecordingStream(
            cfg.application_id, recording_id=recording_id or uuid.uuid4().hex
        )
        self.rec.set_log_time_enabled(False)
        self.rec.save(self.path)
        self.problem = problem
        self.mcts: MCTS | None = None
        self._root: Node | None = None
        self._count = 0
        self._scene_arg = scene
        self._blueprint = blueprint
        self.scene: MujocoScene | None = None
        #: Where the default layout's 3-D view starts (``view_camera``), None: rerun's.
        self._eye: Eye3D | None = None
        self._mj_data: Any = None
        self._scene_done = False
        self._sims: list[int] = []
        self._best: list[float] = []
        self._nodes: list[int] = []
        self._samples: dict[str, NodeSamples] = {}
        self._sample_log = SampleLog(
            scene_root=SCENE,
            plot_root=SAMPLES_2D,
            timeline=SEARCH_TIMELINE,
            height=cfg.floor_height,
            arrow_length=cfg.arrow_length,
            point_radius=cfg.point_radius,
            labels=cfg.sample_labels,
            infeasible_color=cfg.infeasible_color,
        )
        self._drawn: dict[str, str] = {}
        self._scan_from = 0
        self._last_i = -1
        self._last_samples_i = -1
        self._last_tree_i = -1
        self.finished = False
        if problem is not None:
            self._setup_scene(problem)

    # ----- callback ---------------------------------------------------------------------------
    def __call__(self, mcts: MCTS, i: int) -> bool:
        if self.finished:
            raise RuntimeError(
                "this SearchRecorder has finished; create a new one for another search"
            )
        if mcts is not self.mcts or mcts.root is not self._root:
            self._bind(mcts)
        cfg = self.config
        # The recorder's own count, not ``i``: it keeps growing across re-rooting
        # (``MCTS.reroot`` restarts the tree's count), so the timeline never repeats.
        i = self._count
        self._count += 1
        self._last_i = i
        self._sims.append(i)
        curve = mcts.best_return_curve
        self._best.append(curve[-1] if curve else mcts.best_return)
        self._nodes.append(len(mcts.nodes))
        if (i + 1) % cfg.samples_every == 0:
            self._log_samples(i)
        if len(self._sims) >= cfg.flush_every:
            self._flush()
        if cfg.tree_every is not None and (i + 1) % cfg.tree_every == 0:
            self._log_tree(i)
        return False

    def _bind(self, mcts: MCTS) -> None:
        """Start following a (new or re-rooted) tree."""
        self.mcts = mcts
        self._root = mcts.root
        self._samples.clear()
        self._scan_from = 0
        if self.problem is None:
            self.problem = mcts.problem
        if not self._scene_done:
            self._setup_scene(self.problem)

    def _setup_scene(self, problem: Any) -> None:
        self._scene_done = True
        if not self.config.scene or self._scene_arg is False:
            return
        found = find_mujoco(self._scene_arg if self._scene_arg is not None else problem)
        if found is None:
            if self._scene_arg is not None:
                raise ValueError(
                    "scene must be False, None, a (MjModel, MjData) pair or an object holding"
                    f" model/data attributes; found no MuJoCo model in {type(self._scene_arg).__name__}"
                )
            return
        model, data = found
        camera = self.config.view_camera
        if camera == AUTO_CAMERA:
            camera = PERSPECTIVE_CAMERA if PERSPECTIVE_CAMERA in camera_names(model) else None
        # checked before anything is logged: an unknown camera name names the cameras
        self._eye = None if camera is None else model_camera_eye(model, camera)
        self.scene = MujocoScene(model, SCENE, self.config.geom_groups)
        self._mj_data = data
        self.scene.log_geometry(self.rec)

    # ----- watched nodes ----------------------------------------------------------------------
    def watched(self) -> dict[str, Node]:
        """The watched nodes found so far, by entity name."""
        mcts = self.mcts
        out: dict[str, Node] = {}
        if mcts is None:
            return out
        nodes = mcts.nodes
        ops: dict[str, str] = {}
        best_path: list[Node] | None = None
        for entry in self.config.watch:
            name = watch_name(entry)
            if entry == ROOT:
                out[name] = mcts.root
            elif isinstance(entry, str) and entry.startswith(BEST_PREFIX):
                if best_path is None:
                    best_path = [node for node, _ in mcts.best_plan()]
                op = entry[len(BEST_PREFIX) :]
                key = self.config.operator_key
                for node in best_path:
                    if node.info.get(key) == op:
                        out[name] = node
                        break
            elif isinstance(entry, int):
                if entry < len(nodes):
                    out[name] = nodes[entry]
            elif name in self._samples:
                out[name] = self._samples[name].node
            else:
                ops[entry] = name
        if ops:
            key = self.config.operator_key
            stop = len(nodes)
            for k in range(self._scan_from, stop):
                found = nodes[k].info.get(key)
                if isinstance(found, str) and found in ops:
                    out[ops[found]] = nodes[k]
                    del ops[found]
                    if not ops:
                        break
            if ops:  # keep looking from here next time
                self._scan_from = stop
        return out

    def _log_samples(self, i: int) -> None:
        self._last_samples_i = i
        for name, node in self.watched().items():
            cache = self._samples.get(name)
            if cache is None or cache.node is not node:
                cache = self._samples[name] = NodeSamples(node)
            kind = self._sample_log.add(i, cache, name)
            if kind != "none":
                self._drawn[name] = kind

    def _log_tree(self, i: int) -> None:
        mcts = self.mcts
        if mcts is None:
            return
        self._last_tree_i = i
        path = [node for node, _ in mcts.best_plan()]
        path.append(mcts.best_node())
        graph = build_tree_graph(
            mcts.nodes, mcts.root, path, self.config.tree_max_nodes, self.config.infeasible_color
        )
        self.rec.reset_time()
        self.rec.set_time(SEARCH_TIMELINE, sequence=i)
        log_tree(self.rec, TREE, graph)

    def _flush(self) -> None:
        """Send the buffered scalars and sample drawings."""
        self._sample_log.flush(self.rec)
        if not self._sims:
            return
        import rerun as rr

        idx = rr.TimeColumn(SEARCH_TIMELINE, sequence=np.array(self._sims, dtype=np.int64))
        self.rec.send_columns(
            BEST_RETURN, indexes=[idx], columns=rr.Scalars.columns(scalars=np.array(self._best))
        )
        self.rec.send_columns(
            N_NODES,
            indexes=[idx],
            columns=rr.Scalars.columns(scalars=np.array(self._nodes, dtype=np.float64)),
        )
        self._sims.clear()
        self._best.clear()
        self._nodes.clear()

    # ----- the end ----------------------------------------------------------------------------
    def finish(self, result: PlanResult | None = None) -> Path:
        """Log what is logged at the end (last samples, the tree, the plan, the blueprint)
        and close the file. Idempotent; returns the file's path.

        ``result`` is unused except to find the tree when no simulation was recorded.
        """
        if self.finished:
            return self.path
        if self.mcts is None and result is not None and result.mcts is not None:
            self._bind(result.mcts)
        i = max(self._last_i, 0)
        try:
            if self.mcts is not None and self._last_samples_i != self._last_i:
                self._log_samples(i)
            self._flush()
            if self.mcts is not None:
                if self._last_tree_i != self._last_i:
                    self._log_tree(i)
                if self.config.record_plan:
                    self._log_plan()
            self.rec.send_blueprint(
                self._blueprint
                if self._blueprint is not None
                else default_blueprint(
                    has_scene=self.scene is not None or "scene" in self._drawn.values(),
                    has_plot="plot" in self._drawn.values(),
                    has_plan=self.config.record_plan,
                    eye=self._eye,
                )
            )
        finally:
            self.finished = True
            self.rec.flush()
            self.rec.disconnect()
        return self.path

    close = finish

    def __enter__(self) -> SearchRecorder:
        return self

    def __exit__(
        self,
        exc_type: type[BaseException] | None,
        exc: BaseException | None,
        tb: TracebackType | None,
    ) -> None:
        self.finish()

    def _log_plan(self) -> None:
        """Log the best plan on the ``plan`` timeline (and the scene along it)."""
        import rerun as rr

        mcts = self.mcts
        assert mcts is not None
        rec = self.rec
        path = mcts.best_plan()
        gamma = mcts.config.gamma
        ret, disc = 0.0, 1.0
        rec.reset_time()
        # the plan's rewards as one static bar chart: shown on whatever timeline is open
        rewards = np.array([float(node.rewards[e]) for node, e in path], dtype=np.float64)
        rec.log(f"{PLAN}/rewards", rr.BarChart(rewards), static=True)
        rec.set_time(PLAN_TIMELINE, sequence=0)
        rec.log(f"{PLAN}/return", rr.Scalars(0.0))
        for t, (node, e) in enumerate(path, start=1):
            child = node.children[e]
            r = float(node.rewards[e])
            ret += disc * r
            disc *= gamma
            rec.set_time(PLAN_TIMELINE, sequence=t)
            rec.log(f"{PLAN}/reward", rr.Scalars(r))
            rec.log(f"{PLAN}/return", rr.Scalars(ret))
            rec.log(f"{PLAN}/action", rr.BarChart(np.asarray(node.actions[e], dtype=np.float64)))
            rec.log(
                f"{PLAN}/info",
                rr.TextDocument(
                    _info_text(t, node.actions[e], r, node.bonuses[e], node.feasible[e], child.info)
                ),
            )
            for key in (BASE_POSE_KEY, PLACEMENT_KEY):
                pose = pose_of(child.info, key)
                if pose is not None:
                    z = self.config.floor_height
                    L = self.config.arrow_length
                    rec.log(
                        f"{SCENE}/plan/{key}",
                        rr.Arrows3D(
                            origins=[[pose[0], pose[1], z]],
                            vectors=[[L * math.cos(pose[2]), L * math.sin(pose[2]), 0.0]],
                            colors=[[255, 80, 0]],
                            radii=0.02,
                        ),
                    )
        if self.scene is not None:
            self._replay_scene([node.actions[e] for node, e in path])

    def _replay_scene(self, actions: list[Any]) -> None:
        """Body poses at every state of the plan: replay ``actions`` from the root."""
        mcts = self.mcts
        scene = self.scene
        problem = self.problem
        assert mcts is not None and scene is not None
        rec = self.rec
        rec.reset_time()
        rec.set_time(SEARCH_TIMELINE, sequence=0)
        rec.set_time(PLAN_TIMELINE, sequence=0)
        if problem is None or mcts.root.snapshot is None:
            scene.log_poses(rec, self._mj_data)
            return
        before = problem.snapshot()
        try:
            problem.restore(mcts.root.snapshot)
            scene.log_poses(rec, self._mj_data)
            rec.reset_time()
            for t, a in enumerate(actions, start=1):
                res = problem.step(np.asarray(a, dtype=np.float64))
                rec.set_time(PLAN_TIMELINE, sequence=t)
                scene.log_poses(rec, self._mj_data)
                if not getattr(res, "feasible", True) or getattr(res, "terminal", False):
                    if t < len(actions):
                        warnings.warn(
                            f"replaying the best plan: step {t} of {len(actions)} ended the"
                            " episode; the problem is not deterministic?",
                            RuntimeWarning,
                            stacklevel=3,
                        )
                    break
        finally:
            problem.restore(before)


def record_plan(
    problem: Any,
    path: str | os.PathLike[str],
    planner: Any = "voot",
    n_simulations: int = 1000,
    seed: int | None = 0,
    *,
    config: RecorderConfig | None = None,
    scene: Any = None,
    callback: Callback | None = None,
    blueprint: Any = None,
    **planner_options: Any,
) -> PlanResult:
    """Run :func:`voot.tree.plan` with a :class:`SearchRecorder` writing ``path``.

    ``callback`` (e.g. a progress bar) is called too; ``blueprint`` replaces the default
    layout (see :class:`SearchRecorder`); ``planner_options`` are
    :class:`~voot.tree.MCTSConfig` overrides, as for :func:`voot.tree.plan`.
    """
    from voot.tree.planners import plan

    with SearchRecorder(path, problem, config, scene=scene, blueprint=blueprint) as recorder:
        result = plan(
            problem,
            planner,
            n_simulations,
            seed,
            callback=combine_callbacks(recorder, callback),
            **planner_options,
        )
    return result
