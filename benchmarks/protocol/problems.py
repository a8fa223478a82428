"""The planning problems of ``voot-bench plan``: names, paper settings, construction.

A problem is named either

* a **synthetic chain** (:mod:`voot.tree.chains`): ``shekel_chain``, ``griewank_chain``,
  ``rastrigin_chain``, with a dimension (3, 10, 20 have reference thresholds); or
* a **gymnasium id** of any registered environment whose unwrapped env can be
  snapshotted: ``voot/KitchenClearing-v0`` and ``voot/ConveyorPacking-v0`` (aliases
  ``kitchen`` and ``conveyor``), the chains' own ids (``voot/ShekelChain-v0`` with
  ``dim=...`` as an env keyword), or any env with ``get_state``/``set_state``; gymnasium's
  MuJoCo envs (``Reacher-v5`` ...) work through
  :class:`~voot.tree.gym_adapters.MujocoGymProblem`.

Environments are made with ``gymnasium.make(id, disable_env_checker=True, **kwargs)`` and
adapted by the adapter the env offers (its ``planning_problem(env)`` method:
:class:`voot.envs.core.problem.EnvProblem` for the voot robot domains), else by
:class:`~voot.tree.gym_adapters.GymProblem`. Each process keeps the environments it made
(:func:`cached_env`, in the process's worker cache :mod:`voot.parallel.cache`, a small
LRU shared with root-parallel search): a run resets
its env with the run's seed, so a kept env behaves exactly as a fresh one, while the
MuJoCo model is loaded once per process (or Ray actor) instead of once per run.

Per-problem planner settings (:func:`domain_options`) are the authors' where the
reference page gives them: on the chains ``w = 100`` re-evaluations, no decay, root
commitment 5 / 5 / 3, :math:`\\gamma = 0.9`; on the kitchen :math:`\\gamma = 0.9`, on the
conveyor :math:`\\gamma = 0.99` with :math:`\\omega = 0.3` (v0: and 200 feasibility retries
for progressive widening); VOO samples its best cell in ``centered_uniform`` mode on the
chains and ``uniform`` mode on the robot domains. The v1 domains add the authors'
tree-side rules (:data:`V1_TREE_RULES`: 50 retries for every planner, commitment
counting root actions with reward >= 0 at thresholds 10 / 1, the return to the
original root after a goal, VOO's per-operator distance). ``voot/KitchenClearing-v2``
(alias ``kitchen_v2``: kitchens generated from ``layout_seed`` and ``difficulty``, env
keywords) plays the v1 rules and gets the v1 kitchen's settings. ``voot/ConveyorPacking-v2``
(alias ``conveyor_v2``: generated storage rooms on the v1 rules, env keywords
``layout_seed`` and ``difficulty``) gets the v1 conveyor's options on every layout.
"""

from __future__ import annotations

import functools
import json
import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from voot.parallel import CACHE_SIZE, clear_worker_cache, worker_cache

#: The synthetic chains, by problem name -> function name.
CHAINS: Mapping[str, str] = {
    "shekel_chain": "shekel",
    "griewank_chain": "griewank",
    "rastrigin_chain": "rastrigin",
}
#: Short names of gymnasium ids.
ALIASES: Mapping[str, str] = {
    "kitchen": "voot/KitchenClearing-v0",
    "conveyor": "voot/ConveyorPacking-v0",
    "kitchen_v1": "voot/KitchenClearing-v1",
    "conveyor_v1": "voot/ConveyorPacking-v1",
    "kitchen_v2": "voot/KitchenClearing-v2",
    "conveyor_v2": "voot/ConveyorPacking-v2",
}
#: The robot domains under the authors' two-stage protocol, and their tree-side rules
#: (reference page, "What the original code checks inside the retries"): commitment
#: counts root actions with reward >= 0 and returns to the original root once a goal
#: leaf exists; VOO measures the per-operator distance; 50 retries for every planner.
V1_TREE_RULES: Mapping[str, Any] = {
    "commit_min_reward": 0.0,
    "commit_reset_on_goal": True,
    "feasibility_retries": 50,
}
#: Root commitment thresholds of the v1 domains (kitchen 10, conveyor 1).
V1_COMMITMENT: Mapping[str, int] = {
    "voot/KitchenClearing-v1": 10,
    "voot/KitchenClearing-v2": 10,
    "voot/ConveyorPacking-v1": 1,
    "voot/ConveyorPacking-v2": 1,
}
KITCHEN_IDS = frozenset(
    {"voot/KitchenClearing-v0", "voot/KitchenClearing-v1", "voot/KitchenClearing-v2"}
)
CONVEYOR_IDS = frozenset(
    {"voot/ConveyorPacking-v0", "voot/ConveyorPacking-v1", "voot/ConveyorPacking-v2"}
)
#: The chains' gymnasium ids -> function name (their ``dim`` keyword picks the settings).
CHAIN_ENV_IDS: Mapping[str, str] = {
    "voot/ShekelChain-v0": "shekel",
    "voot/GriewankChain-v0": "griewank",
    "voot/RastriginChain-v0": "rastrigin",
}
#: Planners whose per-node sampler is VOO (they get the domain's VOO settings).
VOO_PLANNERS = frozenset({"voot", "voronoi_pw"})
#: Planners choosing among tried actions by UCB after progressive widening.
PW_PLANNERS = frozenset({"pw_uct", "voronoi_pw"})
#: Step-info key of the objects still to handle (recorded at the best leaf).
OBJECTS_KEY = "objects_left"
#: Objects each process keeps (environments among them; the least recently used one is
#: closed): the size of the process's worker cache.
ENV_CACHE_SIZE = CACHE_SIZE


@dataclass(frozen=True)
class PaperSetup:
    """The paper's budget for a problem: simulations per run, seeds, planners compared."""

    simulations: int
    seeds: int
    planners: tuple[str, ...]


#: Planners of the paper's chain experiments (the six samplers).
CHAIN_PLANNERS: tuple[str, ...] = ("voot", "doot", "rand_doot", "pw_uct", "voronoi_pw", "hoot")
#: Planners of the paper's Figure 4.
ROBOT_PLANNERS: tuple[str, ...] = ("voot", "rand_doot", "pw_uct", "voronoi_pw", "doot")
#: The paper's setups (chains: the authors' code; robots: Figure 4).
PAPER_SETUPS: Mapping[str, PaperSetup] = {
    "chain": PaperSetup(10_000, 20, CHAIN_PLANNERS),
    "voot/KitchenClearing-v0": PaperSetup(2_000, 20, ROBOT_PLANNERS),
    "voot/ConveyorPacking-v0": PaperSetup(3_000, 50, ROBOT_PLANNERS),
    "voot/KitchenClearing-v1": PaperSetup(2_000, 20, ROBOT_PLANNERS),
    "voot/KitchenClearing-v2": PaperSetup(2_000, 20, ROBOT_PLANNERS),
    "voot/ConveyorPacking-v1": PaperSetup(3_000, 50, ROBOT_PLANNERS),
    "voot/ConveyorPacking-v2": PaperSetup(3_000, 50, ROBOT_PLANNERS),
}
#: Budget of any other environment.
DEFAULT_SETUP = PaperSetup(1_000, 20, ROBOT_PLANNERS)
#: The default problems of ``voot-bench plan``: the Shekel chain in 10-D and 20-D.
DEFAULT_PROBLEMS: tuple[str, ...] = ("shekel_chain",)
DEFAULT_CHAIN_DIMS: tuple[int, ...] = (10, 20)


def is_chain(problem: str) -> bool:
    return problem in CHAINS


def normalize_problem(name: str) -> str:
    """The canonical problem name: a chain name or a registered gymnasium id.

    ``"Shekel-Chain"`` -> ``"shekel_chain"``, ``"kitchen"`` -> ``"voot/KitchenClearing-v0"``.

    Raises:
        ValueError: neither a chain, an alias nor a registered id; lists the choices.
    """
    text = str(name).strip()
    key = text.lower().replace("-", "_")
    if key in CHAINS:
        return key
    if key in ALIASES:
        return ALIASES[key]
    import gymnasium

    import voot  # noqa: F401 - registers the voot/... ids

    if text in gymnasium.registry:
        return text
    raise ValueError(
        f"unknown problem {name!r}; valid problems are the chains {', '.join(CHAINS)}, the"
        f" aliases {', '.join(f'{a} ({i})' for a, i in ALIASES.items())}, or any registered"
        " gymnasium id whose env has get_state()/set_state() (e.g. voot/ShekelChain-v0)"
    )


def problem_label(problem: str, env_kwargs: Mapping[str, Any] | None = None) -> str:
    """A short display name: the alias of an id if it has one, env keywords appended."""
    short = {v: k for k, v in ALIASES.items()}.get(problem, problem)
    if env_kwargs:
        inner = ", ".join(f"{k}={env_kwargs[k]}" for k in sorted(env_kwargs))
        return f"{short}({inner})"
    return short


def paper_setup(problem: str) -> PaperSetup:
    """Budget, seeds and planners of ``problem`` in the paper (or :data:`DEFAULT_SETUP`)."""
    if is_chain(problem) or problem in CHAIN_ENV_IDS:
        return PAPER_SETUPS["chain"]
    return PAPER_SETUPS.get(problem, DEFAULT_SETUP)


def family(problem: str) -> str:
    """``"chain"`` for the synthetic chains (also through gymnasium), else ``"robot"``."""
    return "chain" if is_chain(problem) or problem in CHAIN_ENV_IDS else "robot"


def check_env_kwargs(env_kwargs: Mapping[str, Any] | None) -> dict[str, Any]:
    """Env keywords must be JSON values (they are part of the run id)."""
    out = dict(env_kwargs or {})
    try:
        json.dumps(out, sort_keys=True, allow_nan=False)
    except (TypeError, ValueError) as exc:
        raise ValueError(f"env keywords must be plain JSON values, got {out!r} ({exc})") from None
    return out


def domain_options(
    problem: str, dim: int | None, planner: str, env_kwargs: Mapping[str, Any] | None = None
) -> dict[str, Any]:
    """:class:`~voot.tree.MCTSConfig` overrides the authors used on ``problem`` for ``planner``.

    See the module docstring; ``sampler_options`` is included for the VOO planners.
    """
    from voot.tree.chains import chain_planner_options

    kwargs = dict(env_kwargs or {})
    if is_chain(problem) or problem in CHAIN_ENV_IDS:
        function = CHAINS.get(problem) or CHAIN_ENV_IDS[problem]
        d = dim if dim is not None else int(kwargs.get("dim", 10))
        chain = chain_planner_options(function, d)
        if planner in VOO_PLANNERS:
            chain["sampler_options"] = {"sampler": "centered_uniform"}
        return chain
    options: dict[str, Any] = {}
    if problem in KITCHEN_IDS:
        options["gamma"] = 0.9
    elif problem in CONVEYOR_IDS:
        options["gamma"] = 0.99
        if planner in PW_PLANNERS and problem == ALIASES["conveyor"]:
            options["feasibility_retries"] = 200
    if problem in V1_COMMITMENT:
        options.update(V1_TREE_RULES, root_commitment=V1_COMMITMENT[problem])
    if problem in ALIASES.values() and planner in VOO_PLANNERS:
        voo: dict[str, Any] = {"sampler": "uniform"}
        if problem in CONVEYOR_IDS:
            voo["omega"] = 0.3
        options["sampler_options"] = voo
        if problem in V1_COMMITMENT:
            options["use_problem_metric"] = True
    return options


# ----- construction ----------------------------------------------------------------------
#: This process's worker cache (:mod:`voot.parallel.cache`), where made environments
#: are kept (under ``("env", id and keywords)``), beside what other users of the process
#: keep (e.g. the problems of root-parallel search).
_ENV_CACHE = worker_cache()


def cached_env(env_id: str, env_kwargs: Mapping[str, Any] | None = None) -> Any:
    """``gymnasium.make(env_id, **env_kwargs)``, kept for later runs in this process."""
    key = ("env", json.dumps([env_id, dict(env_kwargs or {})], sort_keys=True))
    return worker_cache().get(key, functools.partial(_make_env, env_id, env_kwargs), _close_env)


def _make_env(env_id: str, env_kwargs: Mapping[str, Any] | None) -> Any:
    import gymnasium

    import voot  # noqa: F401 - registers the voot/... ids

    return gymnasium.make(env_id, disable_env_checker=True, **dict(env_kwargs or {}))


def _close_env(env: Any) -> None:
    env.close()


def clear_env_cache() -> None:
    """Close and forget every kept environment of this process (this clears the process's
    whole worker cache, :func:`voot.parallel.clear_worker_cache`)."""
    clear_worker_cache()


def adapt_env(env: Any) -> Any:
    """The planning problem of a made (and reset) env, through the adapter that fits it.

    Raises:
        ValueError: the env cannot be snapshotted (says what is missing).
    """
    u = env.unwrapped
    offer = getattr(u, "planning_problem", None)  # the env's own adapter (voot's robot envs)
    if callable(offer):
        return offer(env)
    if callable(getattr(u, "get_state", None)) and callable(getattr(u, "set_state", None)):
        from voot.tree.gym_adapters import GymProblem

        return GymProblem(env)
    if hasattr(u, "model") and hasattr(u, "data"):
        from voot.tree.gym_adapters import MujocoGymProblem

        return MujocoGymProblem(env)
    raise ValueError(
        f"{type(u).__name__} cannot be planned in: its unwrapped env has neither"
        " get_state()/set_state() nor a MuJoCo model/data to snapshot"
    )


@dataclass
class Instance:
    """A problem ready for one run: the planning problem and what the run records.

    Attributes:
        problem: the :class:`~voot.tree.PlanningProblem`, at its initial state.
        objects_initial: objects to handle at the start (``info["objects_left"]`` after
            reset), None if the problem does not report it.
        env: the gymnasium env (None for a direct chain), e.g. to count its steps.
    """

    problem: Any
    objects_initial: float | None
    env: Any = None


def make_instance(
    problem: str,
    dim: int | None,
    env_kwargs: Mapping[str, Any] | None,
    seed: int,
    *,
    cache: bool = True,
) -> Instance:
    """Build ``problem`` for a run with ``seed`` (envs are reset with ``seed``)."""
    if is_chain(problem):
        from voot.tree.chains import make_chain

        if dim is None:
            raise ValueError(f"the {problem} needs a dimension (3, 10 or 20 have references)")
        return Instance(make_chain(CHAINS[problem], int(dim)), None)
    if cache:
        env = cached_env(problem, env_kwargs)
    else:
        import gymnasium

        import voot  # noqa: F401

        env = gymnasium.make(problem, disable_env_checker=True, **dict(env_kwargs or {}))
    _, info = env.reset(seed=int(seed))
    left = info.get(OBJECTS_KEY) if isinstance(info, Mapping) else None
    objects = float(left) if isinstance(left, int | float) and math.isfinite(left) else None
    return Instance(adapt_env(env), objects, env)
