"""The planners of ``voot-bench plan`` by name: their grids and their run configs.

Four kinds of planner run in the planning sweep (:mod:`voot.bench.sweep.plan`): the tree
planners (:class:`voot.tree.MCTS`: ``voot``, ``doot``, ``pw_uct`` ...), the
sampling-based ones (:class:`voot.tree.shooting.ShootingPlanner`: ``cem``, ``mppi`` ...),
outside planners (plug-ins: an installed package's entry point of the group
``voot.planners``, or any ``module:attribute``) and the RL baselines (``ppo``, ``ddpg``,
:mod:`voot.bench.sweep.rl`). All but the RL ones are :class:`voot.planners.Planner`
values in one :data:`REGISTRY`, voot's own registered through the same interface as a
plug-in, each with its grid. This module knows each by name: :data:`PLAN_PLANNERS`,
:func:`normalize_plan_planner`, the hyperparameter grids searched (:func:`planner_grid`),
and the configuration of a run from its problem, planner and parameters
(:func:`run_config`: an :class:`~voot.tree.MCTSConfig`, a
:class:`~voot.tree.shooting.ShootingConfig`, a :class:`PluginConfig` or an
:class:`~voot.rl.RLConfig`; :func:`run_settings`: the keywords its planner function
gets). It runs nothing, so the protocol modules (selection, tuning, ablation) read the
planners here without importing the runs.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, fields
from typing import Any

from voot import validation as V
from voot.bench.protocol import problems as P
from voot.bench.sweep.engine import check_grid
from voot.planners import (
    DEFAULT_DISCOUNT,
    Planner,
    PlannerError,
    PlannerRegistry,
    builtin_planner,
)
from voot.tree.shooting import is_shooting_planner

#: Planners in plotting order (the paper's first).
PLAN_PLANNERS: tuple[str, ...] = (
    "voot",
    "doot",
    "rand_doot",
    "pw_uct",
    "voronoi_pw",
    "hoot",
    "uniform_t",
    "cem",
    "mppi",
    "predictive_sampling",
    "random_shooting",
    "ppo",
    "ddpg",
)
#: Re-evaluation counts ``w`` (the paper's :math:`N_r = 1 + w`) searched per family; the
#: authors used 100 on the chains and 5 on the robot domains.
REEVALUATIONS: Mapping[str, tuple[float, ...]] = {"chain": (10, 100), "robot": (2, 5)}
#: VOO's exploration probabilities searched (the original's grid, thinned; 0.001 is the
#: authors' value on the chains, 0.3 on the conveyor).
OMEGAS: tuple[float, ...] = (0.001, 0.1, 0.3)
#: DOO's exploration weights searched (a spread of the authors' DOO grid).
EPSILONS: tuple[float, ...] = (0.001, 0.1, 1.0)
#: Progressive-widening coefficients :math:`k` searched (:math:`\alpha = 0.5` fixed).
PW_KS: tuple[float, ...] = (1.0, 3.0)
#: UCB constants :math:`c` searched for PW-UCT.
UCB_CS: tuple[float, ...] = (0.1, 1.0, 10.0)
#: HOO smoothness scales :math:`\nu_1` searched for HOOT.
HOO_V1S: tuple[float, ...] = (0.1, 1.0, 10.0)
#: CEM's initial standard deviations searched (normalised units; 0.5 is PETS's).
CEM_INIT_STDS: tuple[float, ...] = (0.25, 0.5)
#: Perturbation scales searched for MPPI and predictive sampling (0.1 is MuJoCo MPC's).
SAMPLING_NOISES: tuple[float, ...] = (0.1, 0.3)
#: MPPI temperatures searched (0.01 is MuJoCo MPC's).
MPPI_TEMPERATURES: tuple[float, ...] = (0.01, 0.1)
#: The RL planners of ``voot-bench plan`` (their ``planner_grid`` is the one default
#: setting in both grids: the paper gives no RL hyperparameters to search).
RL_PLANNERS: tuple[str, ...] = ("ppo", "ddpg")
#: The run parameter naming the reference search's planner.
MATCH_PARAM = "match"
#: The default reference planner: the paper's.
DEFAULT_MATCH = "voot"


def planner_grid(planner: str, family: str, grid: str = "paper") -> list[dict[str, Any]]:
    """Hyperparameter settings of ``planner`` on a problem ``family`` (``chain``/``robot``).

    ``grid="default"`` is one empty setting (the planner's and problem's defaults);
    ``grid="paper"`` every combination of the axes below, the paper's selection rule then
    keeps the best mean final return (:mod:`voot.bench.protocol.select`). The paper's appendix
    grids are not public; these span the values the reference page reports.

    ==========  ==================================================
    planner     axes
    ==========  ==================================================
    voot        omega x reevaluations
    doot        epsilon x reevaluations
    rand_doot   epsilon x reevaluations
    uniform_t   reevaluations
    pw_uct      pw_k x ucb_c
    voronoi_pw  omega x pw_k
    hoot        v1
    cem         init_std
    mppi        noise x temperature
    predictive_sampling  noise
    random_shooting      (none)
    ppo, ddpg   (none: the paper gives no RL grid; SB3's defaults)
    an outside  its own ``grid`` (:class:`voot.planners.Planner`)
    ==========  ==================================================

    Each planner's grid is its registry entry's (:data:`REGISTRY`): voot's own are
    registered with these axes (:func:`builtin_axes`).
    """
    key = normalize_plan_planner(planner)
    check_grid(grid)
    if family not in REEVALUATIONS:
        raise ValueError(f"unknown family {family!r}; valid: {', '.join(REEVALUATIONS)}")
    if grid == "default" or is_rl_planner(key):
        return [{}]
    return planner_entry(key).settings_grid(family)


def builtin_axes(planner: str, family: str) -> dict[str, Sequence[Any]]:
    """The axes of voot's own ``planner``'s grid on ``family`` (the table of
    :func:`planner_grid`)."""
    w = REEVALUATIONS[family]
    axes: dict[str, dict[str, Sequence[Any]]] = {
        "voot": {"omega": OMEGAS, "reevaluations": w},
        "doot": {"epsilon": EPSILONS, "reevaluations": w},
        "rand_doot": {"epsilon": EPSILONS, "reevaluations": w},
        "uniform_t": {"reevaluations": w},
        "pw_uct": {"pw_k": PW_KS, "ucb_c": UCB_CS},
        "voronoi_pw": {"omega": OMEGAS, "pw_k": PW_KS},
        "hoot": {"v1": HOO_V1S},
        "cem": {"init_std": CEM_INIT_STDS},
        "mppi": {"noise": SAMPLING_NOISES, "temperature": MPPI_TEMPERATURES},
        "predictive_sampling": {"noise": SAMPLING_NOISES},
    }
    return axes.get(planner, {})


def _builtin_registry() -> PlannerRegistry:
    """voot's tree and sampling-based planners, each with its grid, and the installed
    plug-ins (entry points of ``voot.planners``)."""
    from voot.tree.config import available_planners
    from voot.tree.shooting import available_shooting_planners

    names = [p for p in PLAN_PLANNERS if p not in RL_PLANNERS]
    names += [p for p in available_planners() + available_shooting_planners() if p not in names]
    return PlannerRegistry(
        [builtin_planner(name, functools.partial(builtin_axes, name)) for name in names]
    )


#: Every planner of ``voot-bench plan`` but the RL ones, by name: voot's own (registered
#: through :mod:`voot.planners` like any other), the installed plug-ins, ``module:attr``.
REGISTRY: PlannerRegistry = _builtin_registry()


def planner_entry(name: str) -> Planner:
    """The :class:`~voot.planners.Planner` of a canonical planner name (not an RL one); a
    ValueError naming it if its plug-in fails to load or is no planner."""
    try:
        return REGISTRY.get(name)
    except PlannerError as exc:
        raise ValueError(str(exc)) from exc
    except KeyError as exc:
        raise ValueError(exc.args[0]) from None


def keeps_tree(name: str) -> bool:
    """Whether the canonical planner ``name`` builds a search tree (voot's tree planners:
    the ones a recording can draw)."""
    return not is_rl_planner(name) and not is_shooting_planner(name) and is_builtin(name)


def is_builtin(name: str) -> bool:
    """Whether the canonical planner ``name`` is voot's own (not an outside planner)."""
    return is_rl_planner(name) or planner_entry(name).builtin


def normalize_plan_planner(name: str) -> str:
    """The canonical name of any planner of ``voot-bench plan``: a tree planner, a
    sampling-based one or an RL one (``ppo``, ``ddpg``); a ValueError listing all."""
    from voot.tree.planners import normalize_any_planner

    if is_rl_planner(name):
        return str(name).strip().lower()
    try:
        return normalize_any_planner(name)
    except ValueError:
        pass
    key = str(name).strip()
    if key in REGISTRY:
        planner_entry(key)  # a plug-in that fails to load fails here, naming itself
        return key
    valid = sorted({*REGISTRY.names(), *RL_PLANNERS})
    raise ValueError(
        f"unknown planner {name!r}; valid planners are: {', '.join(valid)}, or an installed"
        " package's planner as module:attribute (e.g. mypkg.planner:greedy)"
    )


def is_rl_planner(name: object) -> bool:
    """Whether ``name`` is an RL planner (``"PPO"``, ``"ddpg"``)."""
    return isinstance(name, str) and name.strip().lower() in RL_PLANNERS


def split_params(planner: str, params: Mapping[str, Any]) -> tuple[str, dict[str, Any]]:
    """``(reference planner, algorithm options)`` of an RL run's ``params``.

    Raises:
        ValueError: the reference is unknown, is itself an RL planner, or an option is
            not a field of the algorithm's config (the message lists the valid ones).
    """
    from voot.rl import rl_config
    from voot.tree.planners import normalize_any_planner

    options = dict(params)
    match = normalize_any_planner(str(options.pop(MATCH_PARAM, DEFAULT_MATCH)))
    if "gamma" in options:
        raise ValueError(
            f"{planner}: gamma is the problem's discount (the reference search's); it is not"
            " a parameter of an RL run"
        )
    rl_config(planner, **options)  # unknown options name the valid ones
    return match, options


def _config_fields() -> set[str]:
    from voot.tree.config import MCTSConfig

    return {f.name for f in fields(MCTSConfig)}


#: ``--set sampler.NAME=VALUE`` sets the per-node sampler's option NAME (e.g. VOO's own
#: ``sampler``, which the tree's ``sampler`` field would otherwise take).
SAMPLER_PREFIX = "sampler."


def tree_options(
    planner: str, params: Mapping[str, Any], domain: Mapping[str, Any]
) -> dict[str, Any]:
    """The :func:`~voot.tree.planner_config` options of a tree planner's run: the problem's
    ``domain`` options (:func:`~voot.bench.protocol.problems.domain_options`), then
    ``params``; a parameter that is no MCTSConfig field goes to the per-node sampler."""
    from voot.tree.config import available_samplers, planner_config

    options = dict(domain)
    sampler_options = dict(options.pop("sampler_options", {}))
    config_fields = _config_fields()
    tree_samplers = set(available_samplers())
    for name, value in params.items():
        if name == "sampler_options":
            raise ValueError("set sampler options by name (e.g. omega=0.3), not sampler_options=")
        if name.startswith(SAMPLER_PREFIX):  # sampler.sampler=gaussian: VOO's own option
            sampler_options[name[len(SAMPLER_PREFIX) :]] = value
        elif name == "sampler" and value not in tree_samplers:
            # not a per-node sampler (voo, doo, uniform ...): the sampler's own option of
            # that name, e.g. VOO's best-cell sampler (gaussian, centered_uniform)
            sampler_options[name] = value
        elif name in config_fields:
            options[name] = value
        else:
            sampler_options[name] = value
    if sampler_options:
        options["sampler_options"] = sampler_options
    base = planner_config(planner)
    if base.sampler == "uniform" and "sampler_options" in options:
        unknown = sorted(options.pop("sampler_options"))
        valid = sorted(config_fields - {"sampler_options"})
        raise ValueError(
            f"planner {planner!r} samples uniformly and takes no sampler option {unknown};"
            f" valid parameters are: {', '.join(valid)}"
        )
    return options


def tree_config(planner: str, params: Mapping[str, Any], domain: Mapping[str, Any]) -> Any:
    """The :class:`~voot.tree.MCTSConfig` of a tree planner's run: ``planner``'s defaults
    with :func:`tree_options`."""
    from voot.tree.config import planner_config

    options = tree_options(planner, params, domain)
    try:
        return planner_config(planner, **options)
    except ValueError as exc:
        if "unknown option" not in str(exc):
            raise
        names = ", ".join(sorted(_config_fields() - {"sampler_options"}))
        raise ValueError(f"{exc}; or a planner parameter (an MCTSConfig field): {names}") from None


@dataclass(frozen=True)
class PluginConfig:
    """The config of an outside planner's run: its name, version, settings and the
    problem's discount (what its row keeps as ``planner_config``)."""

    planner: str
    version: str
    settings: Mapping[str, Any]
    gamma: float

    def to_dict(self) -> dict[str, Any]:
        return {
            "planner": self.planner,
            "version": self.version,
            "gamma": self.gamma,
            **dict(self.settings),
        }


def run_config(
    problem: str,
    dim: int | None,
    planner: str,
    params: Mapping[str, Any],
    env_kwargs: Mapping[str, Any] | None = None,
) -> Any:
    """The config of a run of ``planner`` with ``params`` on ``problem``.

    An RL planner gets an :class:`~voot.rl.RLConfig`: SB3's defaults, the problem's
    discount (the ``gamma`` of the reference planner it is matched with), ``params``. A
    sampling-based one gets a :class:`~voot.tree.shooting.ShootingConfig`: its defaults,
    the problem's discount (the one the tree planners get), ``params``. A tree planner
    gets the :class:`~voot.tree.MCTSConfig` of :func:`tree_config`. An outside planner
    gets a :class:`PluginConfig`: ``params`` (checked against its signature) and the
    problem's discount.
    """
    from voot.tree.shooting import shooting_config

    if is_rl_planner(planner):
        from voot.rl import rl_config

        match, rl_options = split_params(planner, params)
        gamma = float(run_config(problem, dim, match, {}, env_kwargs).gamma)
        return rl_config(planner, gamma=gamma, **rl_options)
    entry = planner_entry(planner)
    options = P.domain_options(problem, dim, planner, env_kwargs)
    if not entry.builtin:
        entry.check_settings(params)
        gamma = float(options.get("gamma", DEFAULT_DISCOUNT))
        return PluginConfig(planner, entry.version, dict(params), gamma)
    if is_shooting_planner(planner):
        return shooting_config(planner, **run_settings(planner, params, options))
    return tree_config(planner, params, options)


def run_settings(
    planner: str, params: Mapping[str, Any], domain: Mapping[str, Any]
) -> dict[str, Any]:
    """The keyword settings the planner function of a (not RL) run receives, from its
    ``params`` and the problem's ``domain`` options
    (:func:`~voot.bench.protocol.problems.domain_options`): a tree planner's
    :func:`tree_options`, a sampling-based one's ``params`` after the problem's discount,
    an outside planner's ``params`` (a ValueError naming it and its settings if its
    function does not take them)."""
    entry = planner_entry(planner)
    if not entry.builtin:
        entry.check_settings(params)
        return dict(params)
    if is_shooting_planner(planner):
        discount = {"gamma": domain["gamma"]} if "gamma" in domain else {}
        return {**discount, **params}
    return tree_options(planner, params, domain)


def horizon_param(planner: str, horizon: int | None) -> dict[str, int | None]:
    """``horizon`` as the planner's own parameters (empty if None): a sampling-based
    planner's sequence length, or a tree's depth limit :math:`H` counted from the root,
    without root commitment (which would let the horizon recede past ``H``)."""
    if horizon is None:
        return {}
    h = V.integer(horizon, "horizon", 1)
    if is_rl_planner(planner):
        raise ValueError(
            f"--horizon sets a planner's depth; the RL planner {planner!r} learns on whole"
            " episodes (set its max_episode_steps instead, e.g. --set max_episode_steps=5)"
        )
    if is_shooting_planner(planner) or not planner_entry(planner).builtin:
        return {"horizon": h}  # an outside planner takes it as a setting, if it has one
    return {"depth_limit": h, "root_commitment": None}
