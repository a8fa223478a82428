"""Synthetic plan rows shared by the tests of voot.bench.report.plan_runs, plan_plot and
plan_tables (a helper, not a test module)."""

from __future__ import annotations

from voot.bench.store.format import Row, make_row


def plan_row(
    returns: list[float],
    *,
    planner: str,
    seed: int,
    problem: str = "voot/KitchenClearing-v0",
    dim: int | None = None,
    params: dict | None = None,
    left: list[float | None] | None = None,
    initial: float | None = 7.0,
    ms: float = 10.0,
    layout: int | None = None,
    variant: str = "",
) -> Row:
    """A finished plan run with the best returns ``returns`` (one per simulation) and,
    if given, ``left`` objects left of ``initial``; ``ms`` milliseconds a simulation."""
    config = {
        "problem": problem,
        "dim": dim,
        "env_kwargs": {} if layout is None else {"layout_seed": layout},
        "planner": planner,
        "params": params or {},
        "simulations": len(returns),
        "seed": seed,
        "protocol": 1,
    }
    if variant:
        config["variant"] = variant
    extra: dict = {
        "elapsed": [ms / 1000.0 * (i + 1) for i in range(len(returns))],
        "simulator_calls": 2 * len(returns),
    }
    if left is not None:
        extra.update(objects_left=left, objects_initial=initial)
    return make_row("plan", config, status="ok", wall_time=1.0, best_so_far=returns, **extra)


def step_curve(before: float, after: float, at: int, n: int) -> list[float]:
    """``n`` values: ``before`` up to simulation ``at`` (counted from 1), ``after`` from it on."""
    return [before] * (at - 1) + [after] * (n - at + 1)


def kitchen_rows() -> list[Row]:
    rows = []
    for seed in range(3):
        # voot: two settings, omega=0.1 is better; it clears everything at simulation 2 or 3
        rows.append(
            plan_row(
                [0.0, 1.0, 2.0 + seed, 3.0],
                planner="voot",
                seed=seed,
                params={"omega": 0.1},
                left=[None, 3.0, 0.0 if seed else 1.0, 0.0],
            )
        )
        rows.append(
            plan_row(
                [0.0, 0.0, 0.0, 0.5],
                planner="voot",
                seed=seed,
                params={"omega": 0.3},
                left=[7.0, 7.0, 7.0, 6.0],
            )
        )
        # pw_uct never clears the path and takes twice as long per simulation
        rows.append(
            plan_row([0.0, 0.5, 0.5, 1.0], planner="pw_uct", seed=seed, left=[7, 6, 5, 5], ms=20.0)
        )
        rows.append(
            plan_row(
                [-1.0, -0.5, -0.2, -0.1], planner="voot", seed=seed, problem="shekel_chain", dim=10
            )
        )
    return rows


def with_costs(r: Row, calls_per_sim: int, cpu_per_sim: float) -> Row:
    n = len(r["best_so_far"])
    out = dict(r)
    out["calls_curve"] = [calls_per_sim * (i + 1) for i in range(n)]
    out["cpu_elapsed"] = [cpu_per_sim * (i + 1) for i in range(n)]
    out["n_steps"] = n
    out["n_feasibility_checks"] = (calls_per_sim - 1) * n
    return out


#: The generated family of :func:`layout_rows` (no env is made: rows only).
LAYOUT_PROBLEM = "voot/KitchenClearing-v2"
#: Its label in tables and figures (the alias of voot.bench.protocol.problems).
LAYOUT_LABEL = "kitchen_v2"
#: Final returns of voot's selected setting per held-out layout and seed: per-layout means
#: 2, 4, 6 (units: mean 4, t-interval half-width 4.303 * 2 / sqrt(3) = 4.968 over 3
#: layouts; the 6 runs taken as independent would give 2.099).
LAYOUT_FINALS: dict[int, tuple[float, float]] = {0: (1.0, 3.0), 1: (4.0, 4.0), 2: (5.0, 7.0)}


def layout_rows() -> list[Row]:
    """Rows of a held-out protocol on :data:`LAYOUT_PROBLEM`: voot with two settings on
    the training layouts 1000-1001 (omega=0.1 wins there) and on the held-out layouts 0-2
    (omega=0.3 would win there), seeds 0-1; pw_uct (one setting) on both."""
    rows = []
    for layout in (1000, 1001):
        for seed in (0, 1):
            rows.append(plan_row([0.0, 1.0, 3.0], planner="voot", seed=seed,
                                 params={"omega": 0.1}, layout=layout, problem=LAYOUT_PROBLEM))  # fmt: skip
            rows.append(plan_row([0.0, 1.0, 2.0], planner="voot", seed=seed,
                                 params={"omega": 0.3}, layout=layout, problem=LAYOUT_PROBLEM))  # fmt: skip
            rows.append(plan_row([0.0, 1.0, 1.0], planner="pw_uct", seed=seed,
                                 layout=layout, problem=LAYOUT_PROBLEM))  # fmt: skip
    for layout, finals in LAYOUT_FINALS.items():
        for seed, final in enumerate(finals):
            left = [7.0, 3.0, 0.0 if seed == 0 else 1.0]
            rows.append(plan_row([0.0, final / 2, final], planner="voot", seed=seed,
                                 params={"omega": 0.1}, layout=layout, problem=LAYOUT_PROBLEM,
                                 left=left))  # fmt: skip
            rows.append(plan_row([0.0, 9.0, 9.0], planner="voot", seed=seed,
                                 params={"omega": 0.3}, layout=layout, problem=LAYOUT_PROBLEM,
                                 left=[7.0, 0.0, 0.0]))  # fmt: skip
            rows.append(plan_row([0.0, 0.5, 1.0], planner="pw_uct", seed=seed,
                                 layout=layout, problem=LAYOUT_PROBLEM, left=[7.0, 6.0, 5.0]))  # fmt: skip
    return rows
