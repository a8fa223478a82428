r"""``voot-bench demo``: VOOT clearing the kitchen, with a recording and a GIF of its best plan.

:func:`run` plans with a tree search (VOOT by default, the authors' settings for object
clearing: :math:`\gamma = 0.9`, VOO drawing uniformly in the best Voronoi cell; on v1 the
authors' tree-side rules too), writes the rerun recording (``kitchen_<planner>.rrd``: the
MuJoCo scene, the best plan on the ``plan`` timeline, the sampled picks and placements of
the root and the first place node coloured by :math:`\hat Q`, the search tree), checks
that it reads back, renders the best plan as a GIF (``kitchen_<planner>.gif``,
:func:`voot.record.kitchen_animation.plan_animation`; most of the demo's time, so a
progress line on stderr counts the plan's actions rendered) and prints the obstacles
cleared.
It runs on ``voot/KitchenClearing-v1`` by default (``env_id`` picks v0, or the generated
kitchens of ``voot/KitchenClearing-v2`` with ``layout_seed`` and ``difficulty``: the
recording then shows that kitchen's walls, counters and mesh objects, and its files are
named after the layout, :func:`output_stem`).

Whether a search clears every obstacle depends on the seed (see ``docs/recordings.md``,
"VOOT on the kitchen"); the demo seed's search clears all seven within
:data:`DEFAULT_SIMULATIONS` on both versions.
"""

from __future__ import annotations

import json
import sys
import time
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from voot import validation as V
from voot.bench.protocol.problems import domain_options
from voot.problems import problem_record, problem_records
from voot.record.kitchen_animation import plan_animation
from voot.tree.config import normalize_planner
from voot.tree.mcts import MCTS
from voot.tree.search import PlanResult, check_n_simulations
from voot.tree.step_info import StepInfo

#: The first release's kitchen (Figure 5 of :func:`figure5` and the v0 results).
KITCHEN_ID = "voot/KitchenClearing-v0"
#: The generated kitchens (:mod:`voot.envs.kitchen.generated.env`): the family that takes
#: ``layout_seed`` and ``difficulty`` (its former id ``voot/KitchenClearing-v2`` too).
GENERATED_ID = "voot/GeneratedKitchen-v0"
#: The kitchen ids the demo runs on: every record of the kitchen family.
KITCHEN_IDS = tuple(r.id for r in problem_records() if r.family == "kitchen")


def is_generated(env_id: str) -> bool:
    """Whether ``env_id`` is a generated kitchen (its record takes layouts)."""
    return problem_record(env_id).layouts


#: The layout of a generated kitchen when :func:`run` is not given one (the env's defaults).
DEFAULT_LAYOUT_SEED = 0
#: See :data:`DEFAULT_LAYOUT_SEED`.
DEFAULT_DIFFICULTY = "easy"
#: The demo's default: the authors' protocol (v1), where a search is about ten times
#: cheaper than on v0 and the demo seed's search clears the path within 600 simulations
#: (other seeds may commit to a dead end; see docs/recordings.md).
DEMO_ENV = "voot/KitchenClearing-v1"
#: Simulations of :func:`run`: the searches that clear the kitchen do so within about
#: 600 (measured: seeds 3 and 6 at 600); 1,000 take about 2 s on v1 (the shared 2-core
#: machine; rendering the GIF then takes 10-25 s).
DEFAULT_SIMULATIONS = 1000
#: Seed of :func:`run`.
DEFAULT_SEED = 0


def planner_options(planner: str) -> dict[str, Any]:
    r"""The authors' :class:`~voot.tree.MCTSConfig` overrides on object clearing (v0).

    :math:`\gamma = 0.9`, and for the planners whose sampler is VOO, VOO's best-cell
    sampler ``uniform`` (the original's): :func:`voot.bench.protocol.problems.domain_options`.
    """
    return options_for(KITCHEN_ID, planner)


def options_for(env_id: str, planner: str) -> dict[str, Any]:
    """The planner's settings on the kitchen ``env_id`` (on v1 with the authors' tree-side
    rules): :func:`voot.bench.protocol.problems.domain_options`."""
    if env_id not in KITCHEN_IDS:
        raise ValueError(f"unknown kitchen {env_id!r}; valid ids are: {', '.join(KITCHEN_IDS)}")
    return domain_options(env_id, None, normalize_planner(planner))


def layout_kwargs(
    env_id: str, layout_seed: int | None = None, difficulty: str | None = None
) -> dict[str, Any]:
    """The ``gym.make`` keywords that choose the kitchen's layout.

    On :data:`GENERATED_ID` they are ``layout_seed`` and ``difficulty`` (None: the
    defaults :data:`DEFAULT_LAYOUT_SEED`, :data:`DEFAULT_DIFFICULTY`; a level not in
    :data:`voot.envs.kitchen.generated.layout.DIFFICULTIES` is an error naming them). The paper's
    kitchens (v0, v1) are one fixed instance: there they are ``{}``, and a layout option
    is a ValueError that says which env takes it.
    """
    if env_id not in KITCHEN_IDS:
        raise ValueError(f"unknown kitchen {env_id!r}; valid ids are: {', '.join(KITCHEN_IDS)}")
    if not is_generated(env_id):
        given = [
            name
            for name, value in (("layout_seed", layout_seed), ("difficulty", difficulty))
            if value is not None
        ]
        if given:
            verb = "choose" if len(given) > 1 else "chooses"
            raise ValueError(
                f"{' and '.join(given)} {verb} a generated kitchen; {env_id} is the paper's"
                f" fixed instance. Use {GENERATED_ID} (generated_kitchen) for generated layouts"
            )
        return {}
    from voot.envs.kitchen.generated.layout import difficulty_level

    seed = V.integer(DEFAULT_LAYOUT_SEED if layout_seed is None else layout_seed, "layout_seed", 0)
    level = DEFAULT_DIFFICULTY if difficulty is None else difficulty
    difficulty_level(level)  # an unknown level names the valid ones
    return {"layout_seed": seed, "difficulty": level}


def output_stem(planner: str, env_kwargs: dict[str, Any] | None = None) -> str:
    """The file name (without suffix) of :func:`run`'s outputs.

    ``kitchen_<planner>`` on the paper's kitchens; on a generated one its layout is in
    the name, ``kitchen_v2_<difficulty>_<layout_seed>_<planner>``, so demos of several
    layouts can share a folder.
    """
    if not env_kwargs:
        return f"kitchen_{planner}"
    return f"kitchen_v2_{env_kwargs['difficulty']}_{env_kwargs['layout_seed']}_{planner}"


def make_problem(
    seed: int | None = 0, env_id: str = KITCHEN_ID, env_kwargs: dict[str, Any] | None = None
) -> Any:
    """A fresh kitchen (``gym.make(env_id, **env_kwargs)``) as a planning problem, reset
    with ``seed``; ``env_kwargs`` as :func:`layout_kwargs` gives them."""
    import gymnasium as gym

    import voot  # noqa: F401 - registers the environment ids
    from voot.envs.core.problem import EnvProblem

    if env_id not in KITCHEN_IDS:
        raise ValueError(f"unknown kitchen {env_id!r}; valid ids are: {', '.join(KITCHEN_IDS)}")
    env = gym.make(env_id, disable_env_checker=True, **(env_kwargs or {}))
    return EnvProblem(env, seed=seed)


@dataclass(frozen=True)
class DemoSummary:
    """What :func:`run` did.

    Attributes:
        planner, seed, n_simulations: the search.
        obstacles: obstacles on the path at the start.
        cleared: obstacles the best plan clears.
        plan_length: actions of the best plan.
        best_return: its discounted return (goal bonus excluded; the paper's curve).
        first_all_cleared: the first simulation (1-based) after which the best plan
            cleared every obstacle, or None.
        n_nodes: nodes of the tree.
        search_seconds: wall-clock seconds of the search (with recording).
        total_seconds: wall-clock seconds of :func:`run` (search, checks, video).
        recording: the ``.rrd`` file.
        recording_entities: entities the recording holds (read back).
        video: the GIF, or None.
        video_frames: frames of the GIF.
        layout_seed, difficulty: the generated kitchen's layout (None on v0 and v1,
            whose JSON then has neither key).
    """

    planner: str
    seed: int
    n_simulations: int
    obstacles: int
    cleared: int
    plan_length: int
    best_return: float
    first_all_cleared: int | None
    n_nodes: int
    search_seconds: float
    total_seconds: float
    recording: Path
    recording_entities: int
    video: Path | None
    video_frames: int
    layout_seed: int | None = None
    difficulty: str | None = None

    def to_dict(self) -> dict[str, Any]:
        """Plain values (paths as strings), e.g. for JSON; the layout keys only for a
        generated kitchen."""
        out = asdict(self)
        out["recording"] = str(self.recording)
        out["video"] = None if self.video is None else str(self.video)
        for key in ("layout_seed", "difficulty"):
            if out[key] is None:
                del out[key]
        return out


def _check_dir(out_dir: str | Path) -> Path:
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise ValueError(f"out_dir must be a folder, got the file {str(out)!r}")
    out.mkdir(parents=True, exist_ok=True)
    return out


def run(
    out_dir: str | Path,
    n_simulations: int = DEFAULT_SIMULATIONS,
    seed: int = DEFAULT_SEED,
    planner: str = "voot",
    *,
    video: bool = True,
    video_size: tuple[int, int] = (320, 240),
    fps: float = 10.0,
    verbose: bool = True,
    env_id: str = DEMO_ENV,
    layout_seed: int | None = None,
    difficulty: str | None = None,
) -> DemoSummary:
    """Plan on the kitchen with ``planner``; write the recording and a GIF of the best plan.

    Args:
        out_dir: folder of ``kitchen_<planner>.rrd``, ``kitchen_<planner>.gif`` and
            ``kitchen_<planner>.json`` (this summary); on a generated kitchen the
            names carry its layout (:func:`output_stem`).
        n_simulations: simulations of the search.
        seed: seed of the environment's reset and of the search.
        planner: a planner name (``voot``, ``pw_uct`` ...; see
            :func:`voot.tree.available_planners`), run with :func:`planner_options`.
        video: also render the GIF.
        video_size: ``(width, height)`` of the GIF.
        fps: frames per second of the GIF.
        verbose: print progress and the obstacles cleared.
        env_id: the kitchen version (:data:`KITCHEN_IDS`; default :data:`DEMO_ENV`, v1).
        layout_seed: the layout seed of a generated kitchen (:data:`GENERATED_ID` only;
            None: :data:`DEFAULT_LAYOUT_SEED`); on v0 or v1 giving it is a ValueError
            (:func:`layout_kwargs`).
        difficulty: the generated kitchen's level (``"easy"``, ``"medium"``, ``"hard"``;
            None: :data:`DEFAULT_DIFFICULTY`); as ``layout_seed``, v2 only.

    Returns:
        A :class:`DemoSummary`; the recording has been read back with
        :func:`voot.record.read_recording` (a ValueError if it does not load).
    """
    check_n_simulations(n_simulations)
    V.integer(seed, "seed", 0)
    key = normalize_planner(planner)
    env_kwargs = layout_kwargs(env_id, layout_seed, difficulty)
    out = _check_dir(out_dir)
    from voot.record.reader import read_recording
    from voot.record.recorder import record_plan

    start = time.perf_counter()
    problem = make_problem(seed, env_id, env_kwargs)
    env = problem.unwrapped
    obstacles = int(env.initial_obstacles)
    stem = output_stem(key, env_kwargs)
    rrd = out / f"{stem}.rrd"
    if verbose:
        where = "".join(f", {k} {v}" for k, v in env_kwargs.items())
        print(
            f"{key} on {env_id}{where}: {n_simulations} simulations, seed {seed},"
            f" {obstacles} obstacles on the path ...",
            flush=True,
        )
    progress = _Progress(obstacles, verbose)
    result = record_plan(
        problem, rrd, key, n_simulations, seed, callback=progress, **options_for(env_id, key)
    )
    search_seconds = time.perf_counter() - start
    rec = read_recording(rrd)
    if rec.timelines["search"].rows == 0 or "/scene/plan/base_pose" not in rec.entities:
        raise RuntimeError(f"the recording {rrd} lacks the search or the plan")
    left = _objects_left(result, obstacles)
    gif: Path | None = None
    n_frames = 0
    if video:
        assert result.mcts is not None
        problem.restore(result.mcts.root.snapshot)
        label = f"{key.upper().replace('_', '-')}, {n_simulations} simulations, seed {seed}"
        if env_kwargs:
            label += f", {env_kwargs['difficulty']} kitchen {env_kwargs['layout_seed']}"
        talk = _RenderProgress(verbose)
        frames = plan_animation(
            problem, result.actions, size=video_size, label=label, progress=talk
        )
        from voot.record.video import write_video

        talk.writing(len(frames))
        gif = write_video(out / f"{stem}.gif", frames, fps=fps, hold_last=int(2 * fps))
        talk.done()
        from PIL import Image

        with Image.open(gif) as image:  # the writer merges repeated frames: count the file's
            n_frames = int(getattr(image, "n_frames", 1))
    summary = DemoSummary(
        planner=key,
        seed=seed,
        n_simulations=result.n_simulations,
        obstacles=obstacles,
        cleared=obstacles - left,
        plan_length=len(result.actions),
        best_return=float(result.best_return),
        first_all_cleared=progress.first_all_cleared,
        n_nodes=result.n_nodes,
        search_seconds=search_seconds,
        total_seconds=time.perf_counter() - start,
        recording=rrd,
        recording_entities=len(rec.entities),
        video=gif,
        video_frames=n_frames,
        layout_seed=env_kwargs.get("layout_seed"),
        difficulty=env_kwargs.get("difficulty"),
    )
    (out / f"{stem}.json").write_text(json.dumps(summary.to_dict(), indent=2) + "\n")
    if verbose:
        when = (
            f" (all after {summary.first_all_cleared} simulations)"
            if summary.first_all_cleared is not None
            else ""
        )
        print(
            f"{key}: cleared {summary.cleared} of {obstacles} obstacles{when}; best return"
            f" {summary.best_return:.3f}, plan of {summary.plan_length} actions,"
            f" {summary.n_nodes} nodes, search {search_seconds:.1f} s"
        )
        print(f"recording -> {rrd} (open with: rerun {rrd})")
        if gif is not None:
            print(f"video -> {gif} ({n_frames} frames)")
    return summary


def _objects_left(result: PlanResult, obstacles: int) -> int:
    """Obstacles left at the end of the best plan (all of them for an empty plan)."""
    left = StepInfo.of(result.best_leaf_info).objects_left if result.actions else None
    if left is None:
        return obstacles
    # An infeasible last action reports the count of the state it was tried from.
    return int(left)


class _RenderProgress:
    """Progress of the GIF on stderr: one line that counts the plan's actions rendered
    (rewritten in place on a terminal, one line per action otherwise), then the writing."""

    def __init__(self, verbose: bool) -> None:
        self.verbose = verbose
        self._t0 = time.perf_counter()
        self._tty = sys.stderr.isatty()

    def _say(self, text: str, *, final: bool = False) -> None:
        if not self.verbose:
            return
        seconds = time.perf_counter() - self._t0
        line = f"  GIF: {text}, {seconds:4.1f} s"
        if self._tty:
            sys.stderr.write(f"\r{line:<60}" + ("\n" if final else ""))
        else:
            sys.stderr.write(line + "\n")
        sys.stderr.flush()

    def __call__(self, k: int, n: int) -> None:
        self._say(f"rendering the plan's frames, {k} of {n} actions")

    def writing(self, frames: int) -> None:
        self._say(f"writing {frames} frames")

    def done(self) -> None:
        self._say("written", final=True)


class _Progress:
    """Search callback: note when the best plan first clears everything; print now and then."""

    def __init__(self, obstacles: int, verbose: bool, every: int = 100) -> None:
        self.obstacles = obstacles
        self.verbose = verbose
        self.every = every
        self.first_all_cleared: int | None = None
        self._t0 = time.perf_counter()

    def __call__(self, mcts: MCTS, i: int) -> bool:
        left = StepInfo.of(mcts.best_node().info).objects_left
        left = self.obstacles if left is None else left
        if left == 0 and self.first_all_cleared is None:
            self.first_all_cleared = i + 1
        if self.verbose and (i + 1) % self.every == 0:
            print(
                f"  {i + 1:>5} simulations: best return {mcts.best_return:7.3f},"
                f" {self.obstacles - int(left)} cleared, {time.perf_counter() - self._t0:5.1f} s",
                flush=True,
            )
        return False
