r"""``voot-bench figure5``: the paper's Figure 5 on the kitchen, recorded.

:func:`figure5` records the placements sampled at the place node of the first object once
it has been visited ``visits`` (50) times, for VOOT and PW-UCT (or any planners) on the
same seed, and draws them side by side from the recordings over the kitchen's floor plan
(:func:`voot.record.figure5.samples_figure`).

Every placement drawn at the node is counted in one category (:class:`Figure5Run`):
rejected by the pre-check (the feasibility check the retries make; on v1 the cheap
kinematic one), executed and feasible, or executed and failed, by the reason in the
environment's step info (its ``reason_code``: on v1 ``forbidden room`` and ``no base
path``, which only execution finds). The counts are shown next to each panel of the
image, in the recording (a text panel) and written as JSON beside the image.
"""

from __future__ import annotations

import json
import time
from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from voot import validation as V
from voot.bench.demos.kitchen_demo import (
    DEFAULT_SEED,
    KITCHEN_ID,
    _check_dir,
    make_problem,
    options_for,
)
from voot.tree.config import normalize_planner
from voot.tree.mcts import MCTS
from voot.tree.planners import plan
from voot.tree.search import check_n_simulations
from voot.tree.step_info import StepInfo

#: The kitchens Figure 5 is drawn on: the paper's one fixed kitchen (v0, v1).
FIGURE5_IDS = ("voot/KitchenClearing-v0", "voot/KitchenClearing-v1")
#: Visits of the first object's place node at which Figure 5 is drawn (the paper's 50).
FIGURE5_VISITS = 50
#: Colour (RGB) of the executed placements that failed (forbidden rooms, no base path).
EXECUTION_FAILED_COLOR = (220, 40, 40)


@dataclass(frozen=True)
class Figure5Run:
    """One planner's recording for Figure 5.

    Attributes:
        planner: the planner.
        recording: the ``.rrd`` file (stopped when the node reached ``visits``).
        node_id: id of the first object's place node that reached ``visits`` first.
        n_simulations: simulations run (the search timeline's last index is one less).
        visits: the node's visits at the end.
        n_samples: placements executed at the node (its edges; they passed the
            feasibility check, or were the last of ``feasibility_retries`` proposals).
        n_feasible: how many of them were feasible.
        n_rejected: proposals the feasibility check rejected at the node (infeasible
            placements the search never executed).
        entity: the recording's entity of the node's placements (coloured by Q-hat);
            the rejected proposals are in the sibling entity ``.../rejected``.
        view: the name of the 3-D view in the recording's layout.
        execution_failures: executed placements that failed, per ``reason_code`` of
            their step info.
        precheck_failures: rejected proposals per ``reason_code`` of the pre-check's info.
    """

    planner: str
    recording: Path
    node_id: int
    n_simulations: int
    visits: int
    n_samples: int
    n_feasible: int
    n_rejected: int
    entity: str
    view: str
    execution_failures: dict[str, int] = field(default_factory=dict)
    precheck_failures: dict[str, int] = field(default_factory=dict)

    @property
    def n_drawn(self) -> int:
        """Placements drawn at the node: executed ones and those the pre-check rejected."""
        return self.n_samples + self.n_rejected

    def counts(self) -> dict[str, Any]:
        """The counts as plain values (the JSON written beside the image)."""
        return {
            "node_id": self.node_id,
            "simulations": self.n_simulations,
            "visits": self.visits,
            "drawn": self.n_drawn,
            "precheck_failed": self.n_rejected,
            "precheck_failures": dict(sorted(self.precheck_failures.items())),
            "executed": self.n_samples,
            "feasible": self.n_feasible,
            "execution_failed": self.n_samples - self.n_feasible,
            "execution_failures": dict(sorted(self.execution_failures.items())),
        }

    def counts_text(self) -> str:
        """The counts in a few lines (beside each panel, and in the recording)."""
        fails = ", ".join(f"{k} {v}" for k, v in sorted(self.execution_failures.items()))
        return (
            f"{self.n_drawn} placements drawn: {self.n_feasible} feasible;"
            f"\nfailed at execution: {self.n_samples - self.n_feasible}"
            + (f" ({fails})" if fails else "")
            + f";\nfailed the pre-check: {self.n_rejected}"
        )

    @property
    def failed_entity(self) -> str:
        """The entity of the executed placements that failed (red; drawn only if any)."""
        return self.entity.rsplit("/", 1)[0] + "/failed_at_execution"

    def panel_entities(self) -> list[str]:
        """The entities of the image's panel, drawn in this order."""
        extra = [self.failed_entity] if self.n_samples > self.n_feasible else []
        return [self.rejected_entity, self.entity, *extra]

    @property
    def counts_entity(self) -> str:
        """The entity of the counts' text in the recording."""
        return self.entity.rsplit("/", 1)[0] + "/counts"

    @property
    def rejected_entity(self) -> str:
        """The entity of the rejected proposals."""
        return self.entity.rsplit("/", 1)[0] + "/rejected"


def _state_key(snapshot: Any) -> tuple[Any, bytes]:
    """A hashable key of an environment snapshot (task progress and physics)."""
    return snapshot.task, snapshot.physics.tobytes()


class ProposalLog:
    """A planning problem that notes every feasibility check (delegates to an EnvProblem).

    The tree only keeps the actions it executed; a new action is proposed until one
    passes the feasibility check, so the rejected proposals, where a sampler wastes its
    effort (the point of the paper's Figure 5), are not in it. This wrapper notes each
    check: the state it was made in, the step info (pose of the robot and the object)
    and the answer.
    """

    def __init__(self, problem: Any) -> None:
        self.problem = problem
        self.env = problem.env
        self.unwrapped = problem.unwrapped
        #: ``(state key, info, feasible)`` of every check, in order.
        self.checks: list[tuple[tuple[Any, bytes], Any, bool]] = []

    def __getattr__(self, name: str) -> Any:
        """Everything else of the problem (its ``action_metric``, ``n_simulator_calls``
        ...), so that the search sees the same problem with and without the log: a
        missing ``action_metric`` would make VOO fall back to the Euclidean distance."""
        if name == "problem":  # not set yet (e.g. while unpickling)
            raise AttributeError(name)
        return getattr(self.problem, name)

    def snapshot(self) -> Any:
        return self.problem.snapshot()

    def restore(self, snapshot: Any) -> None:
        self.problem.restore(snapshot)

    def step(self, action: Any) -> Any:
        return self.problem.step(action)

    def action_bounds(self) -> Any:
        return self.problem.action_bounds()

    def is_feasible(self, action: Any) -> bool:
        key = _state_key(self.problem.snapshot())
        ok = bool(self.problem.is_feasible(action))
        check = self.problem.last_check
        self.checks.append((key, {} if check is None else check.info, ok))
        return ok

    def rejected(self, snapshot: Any, key: str = "placement") -> NDArray[np.float64]:
        """Poses ``info[key]`` ``(n, 3)`` of the rejected proposals made in ``snapshot``."""
        state = _state_key(snapshot)
        poses = [
            info[key]
            for k, info, ok in self.checks
            if not ok and k == state and info.get(key) is not None
        ]
        return np.array(poses, dtype=np.float64).reshape(-1, 3)

    def rejected_codes(self, snapshot: Any) -> list[str]:
        """The pre-check's reason codes of the rejected proposals made in ``snapshot``."""
        state = _state_key(snapshot)
        return [
            StepInfo.of(info).reason_code for k, info, ok in self.checks if not ok and k == state
        ]


def _first_place_node(mcts: MCTS, visits: int) -> int | None:
    """Id of a child of the root (a place node of the first object) with ``visits`` visits."""
    for child in mcts.root.children:
        if (
            child.visits >= visits
            and child.expandable
            and StepInfo.of(child.info).next_operator == "place"
        ):
            return child.id
    return None


def figure5(
    out_dir: str | Path,
    seed: int = DEFAULT_SEED,
    planners: Sequence[str] = ("voot", "pw_uct"),
    visits: int = FIGURE5_VISITS,
    max_simulations: int = 2000,
    *,
    image: str | None = "kitchen_figure5.png",
    verbose: bool = True,
    env_id: str = KITCHEN_ID,
    counts: str | None = None,
) -> dict[str, Figure5Run]:
    """Record each planner until the first object's place node has ``visits`` visits.

    Paper Figure 5: the placements sampled at the place node of the first object after
    50 visits. A first search (not recorded) finds which place node gets there first
    and after how many simulations; the search is deterministic, so a second one,
    recorded with that node watched (``watch=("root", node_id)``), stops at the same
    point. That recording also holds, at its last simulation, the proposals the
    feasibility check rejected at the node (:class:`ProposalLog`), in the infeasible
    colour, and opens on a Figure-5 layout (:func:`figure5_blueprint`). The panels are
    then drawn from the recordings over the floor plan
    (:func:`voot.record.figure5.samples_figure`) into ``image`` (None: no image), each
    panel with its counts (:meth:`Figure5Run.counts_text`), which go to the JSON file
    ``counts`` in ``out_dir`` too (default: the image's name with ``.json``; none if
    both are None).

    Raises:
        ValueError: if no place node gets ``visits`` visits within ``max_simulations``.
    """
    if env_id not in FIGURE5_IDS:  # the generated kitchens have no layout option here
        raise ValueError(
            f"figure5 runs on the paper's kitchen; valid ids are: {', '.join(FIGURE5_IDS)}"
            f" (got {env_id!r})"
        )
    V.integer(visits, "visits", 1)
    check_n_simulations(max_simulations)
    out = _check_dir(out_dir)
    import rerun as rr

    from voot.record.blueprint import SCENE, SEARCH_TIMELINE
    from voot.record.config import RecorderConfig
    from voot.record.recorder import SearchRecorder

    runs: dict[str, Figure5Run] = {}
    for planner in planners:
        key = normalize_planner(planner)
        options = options_for(env_id, key)
        found: list[int] = []

        def stop(mcts: MCTS, i: int, found: list[int] = found) -> bool:
            node = _first_place_node(mcts, visits)
            if node is not None:
                found.append(node)
            return node is not None

        t0 = time.perf_counter()
        first = plan(
            make_problem(seed, env_id), key, max_simulations, seed, callback=stop, **options
        )
        if not found:
            raise ValueError(
                f"{key}: no place node of the first object got {visits} visits within"
                f" {max_simulations} simulations (seed {seed}); raise max_simulations"
            )
        node_id, n_sims = found[0], first.n_simulations
        rrd = out / f"kitchen_figure5_{key}.rrd"
        folder = f"{SCENE}/samples/node_{node_id}"
        name = key.upper().replace("_", "-")
        view = f"{name}: placements at the first place node ({visits} visits)"
        config = RecorderConfig(watch=("root", node_id), point_radius=0.09, arrow_length=0.3)
        problem = ProposalLog(make_problem(seed, env_id))
        with SearchRecorder(rrd, problem, config, blueprint=figure5_blueprint(view, folder)) as rec:
            res = plan(problem, key, n_sims, seed, callback=rec, **options)
            assert res.mcts is not None
            node = res.mcts.nodes[node_id]
            rejected = problem.rejected(node.snapshot)
            run = Figure5Run(
                planner=key,
                recording=rrd,
                node_id=node_id,
                n_simulations=n_sims,
                visits=node.visits,
                n_samples=len(node.actions),
                n_feasible=int(sum(node.feasible)),
                n_rejected=len(rejected),
                entity=f"{folder}/placements",
                view=view,
                execution_failures=dict(
                    Counter(
                        StepInfo.of(child.info).reason_code
                        for child, ok in zip(node.children, node.feasible, strict=True)
                        if not ok
                    )
                ),
                precheck_failures=dict(Counter(problem.rejected_codes(node.snapshot))),
            )
            rec.rec.reset_time()
            rec.rec.set_time(SEARCH_TIMELINE, sequence=n_sims - 1)
            rec.rec.log(
                f"{folder}/rejected",
                rr.Points3D(
                    np.column_stack([rejected[:, :2], np.full(len(rejected), config.floor_height)]),
                    colors=np.tile(
                        np.array(config.infeasible_color, dtype=np.uint8), (len(rejected), 1)
                    ),
                    radii=0.6 * config.point_radius,
                ),
            )
            xmin, xmax, ymin, ymax = problem.unwrapped.config.forbidden
            rec.rec.log(
                f"{SCENE}/forbidden_rooms",
                rr.Boxes3D(
                    centers=[[0.5 * (xmin + xmax), 0.5 * (ymin + ymax), 0.005]],
                    half_sizes=[[0.5 * (xmax - xmin), 0.5 * (ymax - ymin), 0.005]],
                    colors=[[230, 80, 80, 60]],
                    fill_mode="solid",
                ),
                static=True,
            )
            failed = [
                StepInfo.of(child.info).placement
                for child, ok in zip(node.children, node.feasible, strict=True)
                if not ok
            ]
            xy = np.array([p[:2] for p in failed if p is not None], dtype=np.float64)
            if xy.size:
                rec.rec.log(
                    run.failed_entity,
                    rr.Points3D(
                        np.column_stack(  # a little above the grey ones at the same spots
                            [xy.reshape(-1, 2), np.full(len(xy), config.floor_height + 0.02)]
                        ),
                        colors=np.tile(
                            np.array(EXECUTION_FAILED_COLOR, dtype=np.uint8), (len(xy), 1)
                        ),
                        radii=1.2 * config.point_radius,
                    ),
                )
            rec.rec.log(
                run.counts_entity,
                rr.TextDocument(
                    f"**{name}**, {visits} visits\n\n" + "\n\n".join(run.counts_text().split("\n")),
                    media_type=rr.MediaType.MARKDOWN,
                ),
            )
        if node.visits != first.mcts.nodes[node_id].visits:  # type: ignore[union-attr]
            raise RuntimeError(
                "the recorded search differs from the first one (not deterministic?)"
            )
        runs[key] = run
        if verbose:
            fails = ", ".join(f"{k} {v}" for k, v in sorted(run.execution_failures.items()))
            print(
                f"{key}: place node {node_id} reached {node.visits} visits after {n_sims}"
                f" simulations; {run.n_drawn} placements drawn: {run.n_samples} executed"
                f" ({run.n_feasible} feasible{'; failed: ' + fails if fails else ''}),"
                f" {len(rejected)} rejected by the feasibility check"
                f" ({time.perf_counter() - t0:.1f} s) -> {rrd}",
                flush=True,
            )
    counts_name = counts or (str(Path(image).with_suffix(".json")) if image else None)
    if counts_name is not None and runs:
        meta = {"env_id": env_id, "seed": seed, "visits": visits}
        data = {**meta, "planners": {k: r.counts() for k, r in runs.items()}}
        (out / counts_name).write_text(json.dumps(data, indent=1) + "\n")
        if verbose:
            print(f"counts -> {out / counts_name}")
    if image is not None and runs:
        from voot.record.figure5 import samples_figure

        env = make_problem(seed, env_id).unwrapped
        names = {k: k.upper().replace("_", "-") for k in runs}
        fig = samples_figure(
            {names[k]: r.recording for k, r in runs.items()},
            out / image,
            {names[k]: r.panel_entities() for k, r in runs.items()},
            xlim=(env.config.house[0] - 0.1, env.config.house[1] + 0.1),
            ylim=(env.config.house[2] - 0.1, env.config.house[3] + 0.1),
            point_size=10.0,
            background=floor_plan(env),
            notes={names[k]: r.counts_text() for k, r in runs.items()},
            title=(
                f"Placements sampled at the first object's place node after {visits} visits"
                f" (seed {seed}): colour = Q-hat (viridis), grey = infeasible, red ="
                " failed at execution"
            ),
        )
        if verbose:
            print(f"figure -> {fig}")
    return runs


def figure5_blueprint(title: str, folder: str) -> Any:
    """The viewer layout of a Figure-5 recording.

    Left: the house seen from above (south, slightly tilted) with only the samples
    under ``folder`` (the watched node's placements coloured by :math:`\\hat Q` and
    its rejected proposals in grey) and the forbidden rooms shaded red; right: the
    best return and the tree size over simulations. The time panel opens paused on the
    ``search`` timeline, whose last index is the moment the node reached its visits.
    """
    import rerun.blueprint as rrb

    from voot.record.blueprint import BEST_RETURN, N_NODES, SCENE, SEARCH_TIMELINE

    main = rrb.Spatial3DView(
        origin=f"/{SCENE}",
        name=title,
        contents=[
            f"+ /{SCENE}/**",
            f"- /{SCENE}/samples/**",
            f"- /{SCENE}/plan/**",
            f"+ /{folder}/placements",
            f"+ /{folder}/rejected",
            f"+ /{folder}/failed_at_execution",
            f"+ /{SCENE}/forbidden_rooms",
        ],
        eye_controls=rrb.EyeControls3D(
            position=(2.0, -3.4, 8.8), look_target=(2.0, 0.25, 0.0), eye_up=(0.0, 0.0, 1.0)
        ),
        line_grid=False,
    )
    side = rrb.Vertical(
        rrb.TextDocumentView(origin=f"/{folder}/counts", name="Samples at the node"),
        rrb.TimeSeriesView(origin=f"/{BEST_RETURN}", name="Best return"),
        rrb.TimeSeriesView(origin=f"/{N_NODES}", name="Tree nodes"),
    )
    return rrb.Blueprint(
        rrb.Horizontal(main, side, column_shares=[3, 1]),
        rrb.TimePanel(timeline=SEARCH_TIMELINE, play_state="paused", state="collapsed"),
        collapse_panels=True,
    )


def floor_plan(env: Any) -> Callable[[Any], None]:
    """A :func:`~voot.record.figure5.samples_figure` background: the kitchen from above.

    Static obstacles in grey, the movable objects at the start in tan, the forbidden
    rooms shaded red, the fixed path to the sink as a blue line.
    """
    from matplotlib.patches import Polygon, Rectangle

    statics = [np.asarray(b.corners()) for b in env.static_boxes]
    objects = [np.asarray(env.object_box(i).corners()) for i in range(len(env.objects))]
    fx0, fx1, fy0, fy1 = env.config.forbidden
    path = np.asarray(env.path.waypoints)

    def draw(ax: Any) -> None:
        ax.add_patch(
            Rectangle((fx0, fy0), fx1 - fx0, fy1 - fy0, color=(0.9, 0.3, 0.3, 0.12), zorder=0)
        )
        for c in statics:
            ax.add_patch(Polygon(c, closed=True, color=(0.84, 0.84, 0.84), zorder=1))
        for c in objects:
            ax.add_patch(Polygon(c, closed=True, color=(0.8, 0.65, 0.45), zorder=2))
        ax.plot(path[:, 0], path[:, 1], color=(0.2, 0.45, 0.9), lw=1.0, zorder=2)

    return draw
