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
reference page gives them, read from each problem's record (:mod:`voot.problems`, declared
by its family beside its env: ``voot.envs.kitchen.problems`` ...): on the chains ``w = 100``
re-evaluations, no decay, root commitment 5 / 5 / 3, :math:`\\gamma = 0.9`; on the kitchen
:math:`\\gamma = 0.9`, on the conveyor :math:`\\gamma = 0.99` with :math:`\\omega = 0.3` (v0: and
200 feasibility retries for progressive widening); VOO samples its best cell in
``centered_uniform`` mode on the chains and ``uniform`` mode on the robot domains. The v1
domains add the authors' tree-side rules (:data:`V1_TREE_RULES`: 50 retries for every
planner, commitment counting root actions with reward >= 0 at thresholds 10 / 1, the
return to the original root after a goal, VOO's per-operator distance). The generated
families (``voot/KitchenClearing-v2``, alias ``kitchen_v2``, and ``voot/ConveyorPacking-v2``,
``conveyor_v2``: env keywords ``layout_seed`` and ``difficulty``) play the v1 rules with
the v1 domain's settings on every layout.
"""

from __future__ import annotations

import functools
import json
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from voot.parallel import CACHE_SIZE, clear_worker_cache, worker_cache
from voot.problems import (  # the paper's planner lists, re-exported for the benchmark
    CHAIN_PLANNERS,  # noqa: F401
    DEFAULT_SETUP,
    ROBOT_PLANNERS,  # noqa: F401
    PaperSetup,
    ProblemRecord,
    find_record,
    problem_records,
)

#: The synthetic chains planned without an env, by problem name -> function name (their
#: settings are those of the chain env of that function, :func:`problem_settings`).
CHAINS: Mapping[str, str] = {
    "shekel_chain": "shekel",
    "griewank_chain": "griewank",
    "rastrigin_chain": "rastrigin",
}
#: The authors' tree-side rules on the problems that play them (a record's ``v1_rules``;
#: reference page, "What the original code checks inside the retries"): commitment
#: counts root actions with reward >= 0 and returns to the original root once a goal
#: leaf exists; VOO measures the per-operator distance; 50 retries for every planner.
V1_TREE_RULES: Mapping[str, Any] = {
    "commit_min_reward": 0.0,
    "commit_reset_on_goal": True,
    "feasibility_retries": 50,
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
#: The default problems of ``voot-bench plan``: the Shekel chain in 10-D and 20-D.
DEFAULT_PROBLEMS: tuple[str, ...] = ("shekel_chain",)
DEFAULT_CHAIN_DIMS: tuple[int, ...] = (10, 20)


def is_chain(problem: str) -> bool:
    return problem in CHAINS


def problem_settings(problem: str) -> ProblemRecord | None:
    """The record of ``problem`` (:mod:`voot.problems`): a recorded id, or the chain env's
    record of a chain planned without an env; None for any other environment."""
    if is_chain(problem):
        return next(r for r in problem_records() if r.chain == CHAINS[problem])
    return find_record(problem) if "/" in problem else None


def aliases() -> dict[str, str]:
    """Every alias -> its id, by version first (v0 of each family, then v1 ...), as the
    paper's tables order the problems."""
    records = sorted(problem_records(), key=lambda r: int(r.id.rsplit("-v", 1)[1]))
    return {a: r.id for r in records for a in r.aliases}


#: What a recorded name means, by kind, in the order the help texts list them.
NAME_MEANINGS: Mapping[str, str] = {
    "protocol": "the paper's protocol (v1 rules)",
    "authors": "the paper's scene on the authors' domain (the exact footprint, their rooms and"
    " big-box ban), on the v1 rules",
    "generated": "generated from layout_seed and difficulty, on the v1 rules",
    "v0": "the first release's rules (v0)",
    "chain": "synthetic chains as gymnasium envs",
}


def name_kind(record: ProblemRecord) -> str:
    """Which of :data:`NAME_MEANINGS` a record is: ``protocol`` (the v1 rules on the
    paper's scene), ``authors`` (the same on the authors' domain), ``generated`` (a
    family generated from layouts), ``v0`` or ``chain``."""
    if record.chain is not None:
        return "chain"
    if record.layouts:
        return "generated"
    if record.authors_domain:
        return "authors"
    return "protocol" if record.v1_rules else "v0"


def recorded_names(family: str | None = None, kinds: Sequence[str] = ("protocol",)) -> list[str]:
    """The aliases of the robot records (of ``family``, or every one) of ``kinds``
    (:func:`name_kind`), in the records' order; former names (records renamed to another
    id, still accepted) are not listed."""
    return [
        alias
        for record in problem_records()
        if record.chain is None
        and record.renamed_to is None
        and family in (None, record.family)
        and name_kind(record) in kinds
        for alias in record.aliases
    ]


def names_text(family: str | None = None, kinds: Sequence[str] = tuple(NAME_MEANINGS)) -> str:
    """The recorded aliases (of ``family``, or every robot family; of ``kinds``) grouped by
    what they mean, for help texts: ``"kitchen_v1 conveyor_v1: the paper's protocol (v1
    rules); ..."``, read from the records (:mod:`voot.problems`), so a help text never
    lists a name that means something else."""
    groups = [(kind, recorded_names(family, (kind,))) for kind in NAME_MEANINGS if kind in kinds]
    return "; ".join(f"{' '.join(names)}: {NAME_MEANINGS[kind]}" for kind, names in groups if names)


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
    short = aliases()
    if key in short:
        return short[key]
    import gymnasium

    if text in gymnasium.registry:
        return text
    raise ValueError(
        f"unknown problem {name!r}; valid problems are the chains {', '.join(CHAINS)}, the"
        f" aliases {', '.join(f'{a} ({i})' for a, i in short.items())}, or any registered"
        " gymnasium id whose env has get_state()/set_state() (e.g. voot/ShekelChain-v0)"
    )


def problem_label(problem: str, env_kwargs: Mapping[str, Any] | None = None) -> str:
    """A short display name: the alias of an id if it has one, env keywords appended."""
    record = find_record(problem) if "/" in problem else None
    short = record.short_name if record is not None and record.id == problem else problem
    if env_kwargs:
        inner = ", ".join(f"{k}={env_kwargs[k]}" for k in sorted(env_kwargs))
        return f"{short}({inner})"
    return short


def paper_setup(problem: str) -> PaperSetup:
    """Budget, seeds and planners of ``problem`` in the paper (or :data:`DEFAULT_SETUP`)."""
    record = problem_settings(problem)
    return record.paper_setup if record is not None else DEFAULT_SETUP


def family(problem: str) -> str:
    """``"chain"`` for the synthetic chains (also through gymnasium), else ``"robot"``."""
    record = problem_settings(problem)
    return "chain" if record is not None and record.chain is not None else "robot"


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

    Read from the problem's record (:func:`problem_settings`; none for an unrecorded env):
    a chain's options by dimension (``dim``, else the ``dim`` keyword, else 10), the
    discount, the progressive-widening planners' retries, the v1 tree rules with the root
    commitment, and for the VOO planners the sampler options and the problem's metric.
    """
    record = problem_settings(problem)
    if record is None:
        return {}
    options: dict[str, Any] = {}
    if record.chain is not None:
        from voot.tree.chains import chain_planner_options

        d = dim if dim is not None else int(dict(env_kwargs or {}).get("dim", 10))
        options = chain_planner_options(record.chain, d)
    if record.discount is not None:
        options["gamma"] = record.discount
    if record.pw_retries is not None and planner in PW_PLANNERS:
        options["feasibility_retries"] = record.pw_retries
    if record.v1_rules:
        options.update(V1_TREE_RULES, root_commitment=record.root_commitment)
    if record.voo_options is not None and planner in VOO_PLANNERS:
        options["sampler_options"] = dict(record.voo_options)
        if record.voo_metric:
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
