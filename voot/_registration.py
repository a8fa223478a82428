"""Gymnasium ids of voot's environments, registered when ``voot`` is imported.

Registration stores entry-point strings only, so it costs nothing and imports no MuJoCo.
"""

from __future__ import annotations

#: id -> entry point ("module:Class"). Filled in by the environment modules' issues.
ENV_IDS: dict[str, str] = {
    # Synthetic planning chains (voot.envs.chains); keyword: dim=3 | 10 | 20.
    "voot/ShekelChain-v0": "voot.envs.chains:ShekelChainEnv",
    "voot/GriewankChain-v0": "voot.envs.chains:GriewankChainEnv",
    "voot/RastriginChain-v0": "voot.envs.chains:RastriginChainEnv",
    # MuJoCo benchmark domains (voot.envs; need the [envs] extra); keyword: config=...
    "voot/KitchenClearing-v0": "voot.envs.kitchen.env:KitchenClearingEnv",
    "voot/ConveyorPacking-v0": "voot.envs.conveyor.env:ConveyorPackingEnv",
    # The same domains under the authors' protocol (two-stage feasibility, see
    # docs/environments.md): the entry points above at their "v1" preset.
    "voot/KitchenClearing-v1": "voot.envs.kitchen.env:KitchenClearingEnv",
    "voot/ConveyorPacking-v1": "voot.envs.conveyor.env:ConveyorPackingEnv",
    # Kitchens generated from a seed under the v1 rules (docs/environments.md, "Generated
    # kitchens"); keywords: layout_seed=int, difficulty="easy" | "medium" | "hard".
    "voot/KitchenClearing-v2": "voot.envs.kitchen.generated.env:GeneratedKitchenEnv",
    # Generated storage rooms on the v1 rules (issue 24); keywords: layout_seed=int,
    # difficulty="easy" | "medium" | "hard" (voot.envs.conveyor.generated.env).
    "voot/ConveyorPacking-v2": "voot.envs.conveyor.generated.env:ConveyorFamilyEnv",
}
#: id -> keyword arguments registered with it.
ENV_KWARGS: dict[str, dict[str, str]] = {
    "voot/KitchenClearing-v1": {"preset": "v1"},
    "voot/ConveyorPacking-v1": {"preset": "v1"},
}


def register_envs() -> None:
    """Register every id in :data:`ENV_IDS` with gymnasium (idempotent)."""
    try:
        import gymnasium
    except ImportError:  # pragma: no cover - gymnasium is a core dependency
        return
    for env_id, entry_point in ENV_IDS.items():
        if env_id not in gymnasium.registry:
            gymnasium.register(
                id=env_id, entry_point=entry_point, kwargs=dict(ENV_KWARGS.get(env_id, {}))
            )
