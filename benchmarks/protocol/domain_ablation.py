"""Domain ablation of the conveyor: each departure from the authors' domain switched on alone.

The planner ablation (:mod:`voot.bench.protocol.ablation`) flips planner options and
leaves the domains alone; here the planners are left out and the domain is flipped.
Each :data:`SWITCHES` entry is a set of :class:`~voot.envs.conveyor.config.ConveyorConfig`
overrides on ``ConveyorPacking-v1``; ``authors_domain`` sets all the implemented ones
at once. The statistics need no planner (cheap, so they come first):

* per node (the start, and the states after 1 and 3 actions of the scripted solution of
  the switch's rooms, "not reached" where those actions fail in the switch's domain):
  of ``draws`` uniform 9-D actions, how many pass the v1 pre-check (every switch sees the
  same draws: common random numbers; with voot's rooms the nodes and the pre-check are
  the same for every switch), and of the first ``executions`` that pass, how many
  execute feasibly;
* random rollouts: from the start, each action uniform and redrawn until it passes the
  pre-check (at most 50 draws, the authors' retries), executed until a step fails or
  every box is placed; the boxes placed;
* whether the scripted solution of the switch's rooms (:mod:`voot.envs.conveyor.scripted`:
  voot's, or the one searched for the authors' rooms) still solves the task, and its
  return (on another scale from one room set to the other: the authors' rooms' paths are
  longer; compare boxes placed, not returns).

``voot-bench measure domain-ablation --out FILE`` writes the store (JSON, a few kB) and
prints :func:`table`; ``--table FILE`` redraws the table from a stored file. VOOT and
PW-UCT at the paper's protocol on each switch are not run here (see
``docs/results-planning.md``, "Domain ablation", for their CPU cost and command).

The switches: ``footprint`` (``base_model="footprint"``: the exact oriented footprint
where the disc finds no path), ``big_box_ban`` (the authors' explicit rule at execution),
``authors_rooms`` (``rooms="authors"``: the walls of the authors' scene). The paths'
start is no departure: in the authors' code every placement's base path starts at
``init_base_conf`` = (0, 1.05, 0), as voot's do (``apply_operator_instance`` of
``problem_environments/conveyor_belt_env.py``: each box is picked, the robot set back to
``init_base_conf``, then its path planned), so there is no switch for it.

The kitchen (``domain="kitchen"``, :data:`KITCHEN_SWITCHES` on ``KitchenClearing-v1``)
has one switch, ``footprint`` (``base_model="footprint"``: the place step's base path
for the exact footprint of base square and held object where the carry disc finds none;
the disc also sizes the kitchen's 0.9 m door). The same statistics, with obstacles
cleared in place of boxes placed; a node is reached when the scripted actions before it
all execute.

The authors' rooms with the exact footprint are slow to execute in (about 10 s of CPU per
exact query deep in the west room): ``executions_for`` bounds the executions per node of
named switches (the store records it, the table shows every rate's denominator).
"""

from __future__ import annotations

import math
import time
from collections.abc import Mapping
from types import MappingProxyType
from typing import Any

import numpy as np

#: The domain switches: ConveyorConfig overrides.
SWITCHES: Mapping[str, Mapping[str, Any]] = MappingProxyType(
    {
        "v1": MappingProxyType({}),
        "footprint": MappingProxyType({"base_model": "footprint"}),
        "big_box_ban": MappingProxyType({"big_box_ban": True}),
        "authors_rooms": MappingProxyType({"rooms": "authors"}),
        "authors_domain": MappingProxyType(
            {"base_model": "footprint", "big_box_ban": True, "rooms": "authors"}
        ),
    }
)
#: The kitchen's domain switches: KitchenConfig overrides (on v1).
KITCHEN_SWITCHES: Mapping[str, Mapping[str, Any]] = MappingProxyType(
    {"v1": MappingProxyType({}), "footprint": MappingProxyType({"base_model": "footprint"})}
)
#: The domains: their problem and switches.
DOMAINS: Mapping[str, tuple[str, Mapping[str, Mapping[str, Any]]]] = MappingProxyType(
    {
        "conveyor": ("voot/ConveyorPacking-v1", SWITCHES),
        "kitchen": ("voot/KitchenClearing-v1", KITCHEN_SWITCHES),
    }
)
#: The nodes: scripted actions taken before the statistics.
NODES = (0, 1, 3)
#: Draws of an action in a rollout before the last one is executed (the authors' 50).
RETRIES = 50


def switches_of(domain: str) -> Mapping[str, Mapping[str, Any]]:
    """The switches of ``domain`` (``"conveyor"`` or ``"kitchen"``)."""
    if domain not in DOMAINS:
        raise ValueError(f"unknown domain {domain!r}; choose from {', '.join(DOMAINS)}")
    return DOMAINS[domain][1]


def make_env(switch: str, domain: str = "conveyor") -> Any:
    """The v1 env of ``domain`` with the overrides of ``switch``."""
    switches = switches_of(domain)
    if switch not in switches:
        raise ValueError(f"unknown switch {switch!r}; choose from {', '.join(switches)}")
    if domain == "kitchen":
        from voot.envs.kitchen.env import KitchenClearingEnv

        return KitchenClearingEnv(preset="v1", **switches[switch])
    from voot.envs.conveyor.env import ConveyorPackingEnv

    return ConveyorPackingEnv(preset="v1", **switches[switch])


def _reached(env: Any, domain: str, depth: int, executed: bool) -> bool:
    """Did the ``depth`` scripted actions reach their node? On the conveyor: their boxes
    are placed (three an action); on the kitchen: every one ``executed``."""
    if domain == "conveyor":
        return bool(env.task.placed == min(env.n, 3 * depth))
    return executed


def measure(
    switch: str,
    draws: int = 2000,
    executions: int = 40,
    rollouts: int = 5,
    seed: int = 0,
    domain: str = "conveyor",
) -> dict[str, Any]:
    """The planner-agnostic statistics of one switch (see the module doc); the row records
    ``executions``, the most executions per node."""
    env = make_env(switch, domain)
    t0 = time.process_time()
    env.reset(seed=seed)
    script = env.solution_actions()
    nodes = []
    for depth in NODES:
        env.reset(seed=seed)
        scripted_ok = True
        for a in script[:depth]:
            scripted_ok &= bool(env.transition(a)[3]["feasible"])
        if not _reached(env, domain, depth, scripted_ok):
            # the scripted actions do not fit this domain: the node is not reached
            nodes.append({"depth": depth, "reached": False})
            continue
        state = env.get_state()
        rng = np.random.default_rng([seed, depth])
        passed = executed = feasible = 0
        for _ in range(draws):
            a = rng.uniform(-1.0, 1.0, env.action_dim)
            ok, _ = env.precheck(a)
            if not ok:
                continue
            passed += 1
            if executed < executions:
                executed += 1
                _, _, _, info = env.transition(a)
                feasible += bool(info["feasible"])
                env.set_state(state)
        nodes.append(
            {"depth": depth, "reached": True, "draws": draws, "passed": passed,
             "executed": executed, "feasible": feasible}
        )  # fmt: skip
    placed = []
    rng = np.random.default_rng([seed, 99])
    for _ in range(rollouts):
        env.reset(seed=seed)
        initial = env.objects_left
        while True:
            for _ in range(RETRIES):
                a = rng.uniform(-1.0, 1.0, env.action_dim)
                if env.precheck(a)[0]:
                    break
            _, terminated, truncated, info = env.transition(a)
            if not info["feasible"] or terminated or truncated:
                break
        placed.append(initial - env.objects_left)
    env.reset(seed=seed)
    ret = 0.0
    solved = True
    for a in script:
        r, terminated, _, info = env.transition(a)
        ret += r
        solved &= bool(info["feasible"])
    return {
        "switch": switch,
        "executions": executions,
        "nodes": nodes,
        "rollouts_placed": placed,
        "scripted_solves": solved and env.task.done,
        "scripted_return": round(ret, 6),
        "cpu_seconds": round(time.process_time() - t0, 1),
    }


def _rate(k: int, n: int) -> str:
    """``k/n`` as a percentage with its Wilson 95% interval."""
    if n == 0:
        return "-"
    p = k / n
    z = 1.96
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    lo, hi = max(0.0, centre - half), min(1.0, centre + half)
    return f"{100 * p:.1f}% ({k}/{n}; {100 * lo:.0f}-{100 * hi:.0f}%)"


def table(store: Mapping[str, Any]) -> str:
    """The store's statistics as a markdown table (one row per switch)."""
    head = ["switch"]
    for depth in NODES:
        head += [f"pre-check, {depth} actions", f"executes, {depth} actions"]
    kitchen = store.get("problem") == DOMAINS["kitchen"][0]
    handled = "obstacles cleared" if kitchen else "boxes placed"
    head += [f"random rollouts: {handled}", "scripted solution"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for row in store["rows"]:
        cells = [f"`{row['switch']}`"]
        for node in row["nodes"]:
            if not node["reached"]:
                cells += ["not reached", "not reached"]
                continue
            cells.append(_rate(node["passed"], node["draws"]))
            cells.append(_rate(node["feasible"], node["executed"]))
        placed = row["rollouts_placed"]
        cells.append(f"mean {np.mean(placed):.1f} ({', '.join(str(p) for p in placed)})")
        cells.append(
            f"solves, return {row['scripted_return']:.2f}" if row["scripted_solves"] else "fails"
        )
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def run(
    switches: tuple[str, ...],
    draws: int,
    executions: int,
    rollouts: int,
    seed: int,
    executions_for: Mapping[str, int] | None = None,
    domain: str = "conveyor",
) -> dict[str, Any]:
    """:func:`measure` every switch of ``domain``; the store. ``executions_for`` maps a
    switch to its own bound on the executions per node (default: ``executions`` for
    every switch).

    Raises:
        ValueError: If ``domain`` is unknown, or ``executions_for`` names an unknown
            switch or a bound below 1.
    """
    known = switches_of(domain)
    bounds = dict(executions_for or {})
    for name, n in bounds.items():
        if name not in known:
            raise ValueError(f"unknown switch {name!r}; choose from {', '.join(known)}")
        if type(n) is not int or n < 1:
            raise ValueError(f"the executions of {name} must be an int >= 1, got {n!r}")
    return {
        "problem": DOMAINS[domain][0],
        "settings": {"draws": draws, "executions": executions, "rollouts": rollouts,
                     "seed": seed, "executions_for": bounds},
        "rows": [measure(s, draws, bounds.get(s, executions), rollouts, seed, domain)
                 for s in switches],
    }  # fmt: skip
