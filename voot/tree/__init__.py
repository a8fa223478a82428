"""Monte Carlo tree search with a pluggable action optimiser at every node (VOOT).

The paper's Algorithms 1-2 over a small planning-problem protocol
(:mod:`voot.tree.problem`). Every planner (VOOT, DOOT, RAND-DOOT, PW-UCT, Voronoi
progressive widening, HOOT) is the same :class:`MCTS` with a different
:class:`MCTSConfig`; the sampling-based MPC planners (CEM, MPPI, predictive sampling,
random shooting: :mod:`voot.tree.shooting`) search open-loop sequences over the same
protocol and return the same :class:`PlanResult`::

    from voot.tree import plan, make_chain
    result = plan(make_chain("shekel", 10), "voot", n_simulations=1000, seed=0)
    result.best_return, result.best_return_curve

This package needs numpy only (gymnasium for the adapters and chain environments);
it never imports MuJoCo at import time.
"""

from voot.tree.chains import (
    CHAIN_SPECS,
    SyntheticChain,
    chain_planner_options,
    make_chain,
)
from voot.tree.config import (
    PLANNERS,
    Backup,
    BestReturnOver,
    FinalAction,
    MCTSConfig,
    Selection,
    available_planners,
    available_samplers,
    planner_config,
)
from voot.tree.execute import EpisodeResult, run_episode
from voot.tree.gym_adapters import GymProblem, MujocoGymProblem
from voot.tree.hoo import HOO, HOOConfig
from voot.tree.mcts import MCTS
from voot.tree.node import Node
from voot.tree.planners import plan
from voot.tree.problem import (
    ActionMetric,
    FeasibilityCheck,
    PlanningProblem,
    SimulatorCalls,
    StepResult,
)
from voot.tree.root_parallel import (
    LocalProcessExecutor,
    MergeRule,
    RootParallelConfig,
    RootParallelResult,
    SerialExecutor,
    TreeExecutor,
    plan_root_parallel,
)
from voot.tree.samplers import ActionSampler, OptimizerSampler, UniformSampler
from voot.tree.search import PlanResult
from voot.tree.shooting import (
    SHOOTING_PLANNERS,
    CEMConfig,
    MPPIConfig,
    PredictiveSamplingConfig,
    RandomShootingConfig,
    ShootingConfig,
    ShootingPlanner,
    available_shooting_planners,
    plan_shooting,
    shooting_config,
)

__all__ = [
    "CHAIN_SPECS",
    "HOO",
    "MCTS",
    "PLANNERS",
    "SHOOTING_PLANNERS",
    "ActionMetric",
    "ActionSampler",
    "Backup",
    "BestReturnOver",
    "CEMConfig",
    "EpisodeResult",
    "FeasibilityCheck",
    "FinalAction",
    "GymProblem",
    "HOOConfig",
    "LocalProcessExecutor",
    "MCTSConfig",
    "MPPIConfig",
    "MergeRule",
    "MujocoGymProblem",
    "Node",
    "OptimizerSampler",
    "PlanResult",
    "PlanningProblem",
    "PredictiveSamplingConfig",
    "RandomShootingConfig",
    "RootParallelConfig",
    "RootParallelResult",
    "Selection",
    "SerialExecutor",
    "ShootingConfig",
    "ShootingPlanner",
    "SimulatorCalls",
    "StepResult",
    "SyntheticChain",
    "TreeExecutor",
    "UniformSampler",
    "available_planners",
    "available_samplers",
    "available_shooting_planners",
    "chain_planner_options",
    "make_chain",
    "plan",
    "plan_root_parallel",
    "plan_shooting",
    "planner_config",
    "run_episode",
    "shooting_config",
]
