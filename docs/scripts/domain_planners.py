"""Redraw the tables of VOOT and PW-UCT on the domain switches.

Reads the committed store ``docs/data/domain-planners-v1``: VOOT and PW-UCT with both
widening tests, each at the setting the ablation selected on the plain v1 domain
(tuning seeds 1000-1004, ``docs/data/ablation-v1``), on ConveyorPacking-v1 with the disc,
with the exact footprint in voot's rooms, and with the authors' domain (footprint, rooms
and big-box ban), and on KitchenClearing-v1 with the disc and with the footprint. Writes
a table per domain between the ``<!-- domain-planners-v1:conveyor -->`` and
``<!-- domain-planners-v1:kitchen -->`` markers of ``docs/results-planning.md``, and
draws their curves (:data:`FIGURE`, objects handled against simulations per domain):

    python docs/scripts/domain_planners.py          # the tables and the figure
    python docs/scripts/domain_planners.py run      # run (or resume) the store's runs

Objects handled (boxes placed, obstacles cleared), not returns, are compared: the
authors' rooms put the returns on another scale (their small boxes travel 16-22 m to
the west room).
"""

from __future__ import annotations

import json
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from voot.bench.cli.main import main as bench
from voot.bench.report import docs_pages
from voot.bench.report.plan_runs import first_reach
from voot.bench.store.frame import store_frame

STORE = Path("docs/data/domain-planners-v1")
PAGE = Path("docs/results-planning.md")
FIGURE = Path("docs/figures/domain-planners/planners.png")

#: Per table (its marker's suffix): the problem, its domains by their ``env_kwargs``
#: (JSON) in the table's order, and the budgets at which objects handled are reported.
TABLES: dict[str, tuple[str, dict[str, str], tuple[int, ...]]] = {
    "conveyor": (
        "voot/ConveyorPacking-v1",
        {
            "{}": "v1 (disc)",
            '{"base_model":"footprint"}': "footprint",
            '{"base_model":"footprint","big_box_ban":true,"footprint_heuristic":"geodesic",'
            '"rooms":"authors"}': "authors_domain",
        },
        (100, 300, 1000),
    ),
    "kitchen": (
        "voot/KitchenClearing-v1",
        {"{}": "v1 (disc)", '{"base_model":"footprint"}': "footprint"},
        (100, 500, 2000),
    ),
}


#: The conveyor's and the kitchen's domains (``env_kwargs``).
CONVEYOR_DOMAINS: tuple[dict[str, Any], ...] = (
    {},
    {"base_model": "footprint"},
    {
        "base_model": "footprint",
        "footprint_heuristic": "geodesic",
        "big_box_ban": True,
        "rooms": "authors",
    },
)
KITCHEN_DOMAINS: tuple[dict[str, Any], ...] = ({}, {"base_model": "footprint"})

#: Per problem: its domains with their seeds, simulations, and each planner's setting as
#: the ablation selected it on the plain v1 domain (tuning seeds 1000-1004,
#: ``docs/data/ablation-v1``; on the conveyor every PW-UCT setting tied there, and the
#: tie goes to the first of the grid). Every domain has 20 seeds (the authors' domain is
#: the faithful conveyor, ``voot/ConveyorPacking-v3``); the other conveyor domains' first
#: 5 and the kitchen's first 10 ran in earlier sessions.
RUNS: dict[
    str, tuple[tuple[tuple[dict[str, Any], range], ...], int, list[tuple[str, dict[str, Any]]]]
] = {
    "conveyor_v1": (
        (
            (CONVEYOR_DOMAINS[0], range(20)),
            (CONVEYOR_DOMAINS[1], range(20)),
            (CONVEYOR_DOMAINS[2], range(20)),
        ),
        1000,
        [
            ("pw_uct", {"pw_k": 0.8, "ucb_c": 0.1, "widening": "authors"}),
            ("pw_uct", {"pw_k": 1.0, "ucb_c": 0.1}),
            ("voot", {"omega": 0.3, "reevaluations": 2}),
        ],
    ),
    "kitchen_v1": (
        tuple((domain, range(20)) for domain in KITCHEN_DOMAINS),
        2000,
        [
            ("pw_uct", {"pw_k": 0.8, "ucb_c": 0.1, "widening": "authors"}),
            ("pw_uct", {"pw_k": 1.0, "ucb_c": 1.0}),
            ("voot", {"omega": 0.3, "reevaluations": 5}),
        ],
    ),
}

#: The paper's protocol on the conveyor (50 seeds, 3,000 simulations; the paper reads
#: VOOT at 1,000 and the others at 3,000) in the authors' domain, for the three settings
#: above. A search is anytime, so a run's first 1,000 simulations are the
#: 1,000-simulation run's on the same seed, which :func:`long_table` checks seed by seed.
#: PW-UCT as the authors built it (their widening) first: it costs the least. Rows:
#: (problem, env_kwargs, seeds, simulations, planner, setting).
LONG_RUNS: list[tuple[str, dict[str, Any], range, int, str, dict[str, Any]]] = [
    ("conveyor_v1", CONVEYOR_DOMAINS[2], range(50), 3000, planner, fixed)
    for planner, fixed in RUNS["conveyor_v1"][2]
]
#: The 3,000-simulation table's budgets (boxes placed at each).
LONG_BUDGETS = (1000, 3000)


def value_text(value: Any) -> str:
    """A setting's value as ``--set`` and ``--env-kwargs`` read it."""
    return str(value).lower() if isinstance(value, bool) else str(value)


def planned() -> list[tuple[str, dict[str, Any], range, int, str, dict[str, Any]]]:
    """The store's planned runs, one entry per command: (problem, env_kwargs, seeds,
    simulations, planner, setting), cheapest first."""
    return [
        (problem, env_kwargs, seeds, simulations, planner, fixed)
        for problem, (domains, simulations, settings) in RUNS.items()
        for env_kwargs, seeds in domains
        for planner, fixed in settings
    ] + list(LONG_RUNS)


def commands(store: str | Path = STORE) -> list[list[str]]:
    """The ``voot-bench plan`` command lines of :func:`planned`."""
    out = []
    for problem, env_kwargs, seeds, simulations, planner, fixed in planned():
        argv = ["plan", "--out", str(store), "--compact", "--problems", problem]
        argv += ["--grid", "default", "--seeds", f"{seeds.start}:{seeds.stop}"]
        argv += ["--simulations", str(simulations), "--planners", planner, "--set"]
        argv += [f"{k}={value_text(v)}" for k, v in fixed.items()]
        if env_kwargs:
            argv += ["--env-kwargs", *(f"{k}={value_text(v)}" for k, v in env_kwargs.items())]
        out.append(argv)
    return out


def specs() -> list[Any]:
    """The store's runs as sweep specs (what :func:`commands` runs)."""
    from voot.bench.sweep.plan import build_plan_specs

    return [
        spec
        for problem, env_kwargs, seeds, simulations, planner, fixed in planned()
        for spec in build_plan_specs(
            [problem],
            planners=[planner],
            seeds=seeds,
            simulations=simulations,
            grid="default",
            env_kwargs=env_kwargs,
            fixed=fixed,
        )
    ]


def handled(objects_left: Sequence[float], initial: float, budget: int) -> float:
    """Objects the best plan (highest return) handles after ``budget`` simulations."""
    return float(initial - objects_left[min(budget, len(objects_left)) - 1])


def kwargs_key(env_kwargs: str | None) -> str:
    """A run's ``env_kwargs`` column (JSON) in the form of :data:`TABLES`' keys."""
    return json.dumps(json.loads(env_kwargs or "{}"), sort_keys=True, separators=(",", ":"))


def mean_range(values: Sequence[float]) -> str:
    """``mean [min, max]`` of ``values``."""
    return f"{np.mean(values):.1f} [{min(values):g}, {max(values):g}]"


def planner_label(planner: str, fixed: dict[str, Any]) -> str:
    """``VOOT (omega 0.3, reevaluations 2)``: the planner and its setting, for the table."""
    name = {"voot": "VOOT", "pw_uct": "PW-UCT"}[planner]
    if fixed.get("widening") == "authors":
        name += " (authors' widening)"
    setting = ", ".join(f"{k} {v}" for k, v in fixed.items() if k != "widening")
    return f"{name} ({setting})"


def keyed(frame: Any) -> Any:
    """``frame`` with its runs' ``env_kwargs`` and setting as comparable keys."""
    return frame.assign(
        key=frame["env_kwargs"].map(kwargs_key),
        setting=frame["params"].map(lambda s: json.dumps(json.loads(s), sort_keys=True)),
    )


def setting_runs(frame: Any, problem: str, key: str, planner: str, fixed: dict[str, Any]) -> Any:
    """The runs of :func:`keyed` ``frame`` on ``problem`` in domain ``key`` by ``planner``
    at setting ``fixed`` (every simulation budget)."""
    return frame[
        (frame["problem"] == problem)
        & (frame["key"] == key)
        & (frame["planner"] == planner)
        & (frame["setting"] == json.dumps(fixed, sort_keys=True))
    ]


def header(head: Sequence[str]) -> list[str]:
    """A Markdown table's header lines: two text columns, the rest right-aligned."""
    return ["| " + " | ".join(head) + " |", "|---|---|" + "---:|" * (len(head) - 2)]


def outcome_cells(runs: Any, budgets: Sequence[int]) -> tuple[list[str], list[str], str]:
    """The runs' objects handled at each budget, (seeds handling all, median simulations
    to all), and their median CPU seconds, as table cells."""
    curves = list(zip(runs["objects_left"], runs["objects_initial"], strict=True))
    firsts = first_reach(np.array([left for left, _ in curves], dtype=float))
    reached = firsts[np.isfinite(firsts)]
    at_budgets = [mean_range([handled(left, n, b) for left, n in curves]) for b in budgets]
    to_all = [
        f"{len(reached)}/{len(runs)}",
        f"{np.median(reached):.0f}" if len(reached) else "—",
    ]
    return at_budgets, to_all, f"{np.median([c[-1] for c in runs['cpu_elapsed']]):.0f}"


def table(frame: Any, name: str) -> str:
    """The Markdown table of the store's runs on table ``name``'s problem, a row per
    domain and planner of :data:`RUNS` (``not run yet`` where the store has none)."""
    problem, domains, budgets = TABLES[name]
    planned_domains, simulations, settings = RUNS[f"{name}_v1"]
    seeds_of = {kwargs_key(json.dumps(kwargs)): seeds for kwargs, seeds in planned_domains}
    what = "boxes placed" if name == "conveyor" else "obstacles cleared"
    head = [
        "domain",
        "planner (setting)",
        "seeds",
        *(f"{what} at {b:,}" for b in budgets),
        f"seeds handling all by {budgets[-1]:,}",
        "median simulations to all",
        "median CPU s per run",
    ]
    lines = header(head)
    frame = keyed(frame[frame["problem"] == problem])
    for key, domain in domains.items():
        seeds = seeds_of[key]
        for planner, fixed in settings:
            runs = setting_runs(frame, problem, key, planner, fixed)
            runs = runs[runs["simulations"] == simulations]
            label = planner_label(planner, fixed)
            if runs.empty:
                lines.append(f"| {domain} | {label} | 0 of {len(seeds)} |" + " not run yet |" * 6)
                continue
            at_budgets, to_all, cpu = outcome_cells(runs, budgets)
            cells = [domain, label, f"{len(runs)} of {len(seeds)}", *at_budgets, *to_all, cpu]
            lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def long_table(frame: Any) -> str:
    """The Markdown table of :data:`LONG_RUNS`: boxes placed at :data:`LONG_BUDGETS`, and
    on how many seeds the first 1,000 simulations are the 1,000-simulation run's (the
    same boxes left after every simulation)."""
    head = [
        "domain",
        "planner (setting)",
        "simulations",
        "seeds",
        *(f"boxes placed at {b:,}" for b in LONG_BUDGETS),
        f"seeds placing all by {LONG_BUDGETS[-1]:,}",
        "median simulations to all",
        "first 1,000 as the 1,000 run's",
        "median CPU s per run",
    ]
    lines = header(head)
    labels = {k: v for _, domains, _ in TABLES.values() for k, v in domains.items()}
    frame = keyed(frame)
    for problem, env_kwargs, seeds, simulations, planner, fixed in LONG_RUNS:
        key = kwargs_key(json.dumps(env_kwargs))
        same = setting_runs(frame, TABLES[problem.removesuffix("_v1")][0], key, planner, fixed)
        runs = same[same["simulations"] == simulations].sort_values("seed")
        label = planner_label(planner, fixed)
        cells = [labels[key], label, f"{simulations:,}", f"{len(runs)} of {len(seeds)}"]
        if runs.empty:
            lines.append("| " + " | ".join(cells) + " |" + " not run yet |" * (len(head) - 4))
            continue
        short = {
            seed: np.asarray(left, dtype=float)
            for seed, left in zip(same["seed"], same["objects_left"], strict=True)
            if len(left) == LONG_BUDGETS[0]
        }
        matched = sum(
            seed in short
            and np.array_equal(np.asarray(left, dtype=float)[: LONG_BUDGETS[0]], short[seed])
            for seed, left in zip(runs["seed"], runs["objects_left"], strict=True)
        )
        compared = sum(seed in short for seed in runs["seed"])
        at_budgets, to_all, cpu = outcome_cells(runs, LONG_BUDGETS)
        cells += [*at_budgets, *to_all, f"{matched} of {compared}", cpu]
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def figure(frame: Any, path: str | Path = FIGURE) -> None:
    """Objects handled against simulations, a panel per problem and domain of
    :data:`TABLES` (its planned runs of :data:`RUNS`): the seeds' mean, and the band
    between their 25th and 75th percentiles, per planner and setting."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    # a panel per domain, and a last column for each row's legend
    width = max(len(domains) for _, domains, _ in TABLES.values()) + 1
    fig, axes = plt.subplots(len(TABLES), width, figsize=(4.0 * width, 3.3 * len(TABLES)))
    frame = keyed(frame)
    for row, (name, (problem, domains, _)) in enumerate(TABLES.items()):
        _, simulations, settings = RUNS[f"{name}_v1"]
        what = "boxes placed" if name == "conveyor" else "obstacles cleared"
        for col in range(len(domains), width):
            axes[row, col].axis("off")
        for col, (key, domain) in enumerate(domains.items()):
            ax = axes[row, col]
            for planner, fixed in settings:
                runs = setting_runs(frame, problem, key, planner, fixed)
                runs = runs[runs["simulations"] == simulations]
                if runs.empty:
                    continue
                curves = np.array(
                    [n - np.asarray(left, dtype=float) for left, n in
                     zip(runs["objects_left"], runs["objects_initial"], strict=True)]
                )  # fmt: skip
                x = np.arange(1, curves.shape[1] + 1)
                (line,) = ax.plot(x, curves.mean(axis=0), label=planner_label(planner, fixed))
                low, high = np.quantile(curves, [0.25, 0.75], axis=0)
                ax.fill_between(x, low, high, color=line.get_color(), alpha=0.15)
            ax.set_xscale("log")
            ax.set_title(f"{name}: {domain}", fontsize=10)
            ax.set_xlabel("simulations")
            ax.set_ylabel(what)
        handles, labels = axes[row, 0].get_legend_handles_labels()
        axes[row, -1].legend(
            handles, labels, loc="center left", fontsize=8,
            title=f"{name}: seeds' mean, 25-75% band", title_fontsize=8,
        )  # fmt: skip
    fig.tight_layout()
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(path, dpi=110)
    plt.close(fig)


def render(store: str | Path) -> dict[str, str]:
    """The page's blocks (marker -> body): a table per domain and the 3,000-simulation
    table, from ``store``."""
    return blocks_of(store_frame(store, kind="plan", status="ok"))


def blocks_of(frame: Any) -> dict[str, str]:
    """:func:`render`'s blocks from the store's frame of finished plan runs."""
    blocks = {f"{STORE.name}:{name}": "\n" + table(frame, name) + "\n" for name in TABLES}
    blocks[f"{STORE.name}:conveyor-3000"] = "\n" + long_table(frame) + "\n"
    return blocks


def main(argv: Sequence[str] = ()) -> None:
    if list(argv) == ["run"]:
        for command in commands():
            print("voot-bench " + " ".join(command), flush=True)
            code = bench([*command, "--workers", "1", "--no-progress"])
            if code != 0:
                raise SystemExit(code)
        return
    if argv:
        raise SystemExit(f"usage: {Path(__file__).name} [run]; got {' '.join(argv)}")
    frame = store_frame(STORE, kind="plan", status="ok")
    docs_pages.rewrite_page(PAGE, blocks_of(frame))
    figure(frame)
    print(f"{STORE.name}: tables redrawn into {PAGE}, curves drawn into {FIGURE}")


if __name__ == "__main__":
    import sys

    main(sys.argv[1:])
