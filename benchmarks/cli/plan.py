"""``voot-bench plan``: planners x problems x seeds (the paper's Figure 4), local or on
Ray, resumable; with ``--tuning-seeds`` the protocol's tuning runs, the selection on them
and the evaluation runs of the selected setting; with ``--layout-seeds`` a layout axis of
a generated family, and with ``--tuning-layouts`` (or ``--heldout``) the held-out
protocol: tuning on training layouts, evaluation on held-out layouts
(:mod:`voot.bench.protocol.layouts`); ``--estimate`` prints the CPU-hours instead of running."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

from voot.bench.cli import common as C
from voot.bench.store.result_store import ResultStore

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers
    from voot.bench.sweep.engine import SweepSummary
    from voot.bench.sweep.plan import PlanSpec


def cmd_plan(args: argparse.Namespace) -> int:
    from voot.bench.protocol.problems import DEFAULT_PROBLEMS
    from voot.bench.sweep.plan import build_plan_specs, summarize_plan_specs

    C.check_sweep_options(args)
    check_plan_outputs(args)
    if args.record is not None:
        if args.backend == "ray":
            raise C.CLIError(
                "--record writes .rrd files where the search runs; use --backend process"
                " (or serial) for recorded runs"
            )
        try:
            from voot.record import SearchRecorder  # noqa: F401 - the recorder's entry point
        except ImportError as exc:
            raise C.CLIError(
                f"--record needs the recorder of voot.record ({exc}); install the [record]"
                " extra (pip install 'voot[record]')"
            ) from None
    layouts = _layout_options(args)
    seeds = C.parse_range(args.seeds, "--seeds") if args.seeds is not None else None
    if seeds is None and layouts.evaluation is not None:
        seeds = [0]  # on a layout axis the layouts are the samples: one seed each by default
    problems = C.split_list(args.problems) or list(DEFAULT_PROBLEMS)

    def specs_of(seed_list: list[int] | None, tuning: bool = False) -> list[PlanSpec]:
        out: list[PlanSpec] = []
        for names, layout_list in layouts.groups(problems, tuning):
            out += build_plan_specs(
                names,
                C.parse_int_list(args.dims, "--dims") or None,
                C.split_list(args.planners) or None,
                seed_list,
                simulations=args.simulations,
                grid=args.grid,
                env_kwargs=C.parse_assignments(args.env_kwargs, "--env-kwargs"),
                fixed=C.parse_assignments(args.set, "--set"),
                record=args.record,
                horizon=args.horizon,
                layout_seeds=layout_list,
            )
        return out

    if args.tuning_seeds is not None or layouts.tuning is not None:
        if args.record is not None:
            raise C.CLIError(
                "--record records single runs; it does not go with --tuning-seeds,"
                " --tuning-layouts or --heldout"
            )
        tuning_seeds = (
            C.parse_range(args.tuning_seeds, "--tuning-seeds")
            if args.tuning_seeds is not None
            else seeds  # held-out layouts: the same seeds on other layouts
        )
        tuning_specs, evaluation_specs = specs_of(tuning_seeds, tuning=True), specs_of(seeds)
        C.check_envs([*tuning_specs, *evaluation_specs], layout_option=_layout_option(args))
        return plan_tuned(args, tuning_specs, evaluation_specs)
    specs = specs_of(seeds)
    C.check_envs(specs, layout_option=_layout_option(args))
    if args.estimate:
        return _print_estimate(args, specs)
    simulations = sum(s.simulations for s in specs)
    print(
        f"{len(specs)} runs, {simulations} simulations{C.stored_note(args.out, specs)}",
        file=sys.stderr,
    )
    if args.dry_run:
        print(summarize_plan_specs(specs))
        return 0
    summary = _run_plan_specs(
        args, specs, C.open_store(args.out, C.compact_config(args) if args.compact else None)
    )
    if args.record is not None and summary.skipped:
        print(
            f"note: {summary.skipped} runs were already in the store and were not recorded"
            " again (use a new --out to record them)",
            file=sys.stderr,
        )
    return 1 if summary.failed else 0


def _layout_option(args: argparse.Namespace) -> str:
    """The option the runs' layout seeds came from, for an error about them."""
    if getattr(args, "heldout", False):
        return "--heldout"
    return "--layout-seeds" if getattr(args, "layout_seeds", None) is not None else "--env-kwargs"


def check_plan_outputs(args: argparse.Namespace) -> None:
    """Refuse an unwritable ``--out`` (the store's folder) or ``--record`` before any
    work (:func:`voot.bench.cli.common.check_output`)."""
    C.check_output(args.out, "--out", folder=True)
    C.check_output(getattr(args, "record", None), "--record")


def _print_estimate(args: argparse.Namespace, specs: Sequence[PlanSpec]) -> int:
    """Print the estimated CPU-hours of ``specs`` (:mod:`voot.bench.protocol.estimate`); run nothing."""
    from voot.bench.protocol.estimate import estimate, format_estimate
    from voot.bench.sweep.engine import pending_specs

    store = C.existing_store(args.out)
    rows = store.load(status="ok") if store is not None else []
    pending = pending_specs(specs, store) if store is not None else list(specs)
    lines = estimate(
        specs, rows, {s.run_id for s in pending}, probe_simulations=args.probe_simulations
    )
    print(format_estimate(lines, args.workers or os.cpu_count() or 1))
    return 0


def _run_plan_specs(
    args: argparse.Namespace, specs: Sequence[PlanSpec], store: ResultStore
) -> SweepSummary:
    """Run ``specs`` into ``store`` with the backend of ``args``; the sweep's summary."""
    from voot.bench.sweep.backends import make_backend

    backend = make_backend(
        args.backend, args.workers, address=args.address, max_tries=args.max_tries
    )
    layout = f", compact: {store.compact}" if store.compact is not None else ""
    print(f"results: {store.path} (backend: {backend.name}{layout})", file=sys.stderr)
    return C.run_specs(args, specs, store, backend)


def plan_tuned(
    args: argparse.Namespace, tuning: Sequence[PlanSpec], candidates: Sequence[PlanSpec]
) -> int:
    """``voot-bench plan --tuning-seeds``: the grid on the tuning seeds, the selection on
    them, the selected setting on the evaluation seeds (:mod:`voot.bench.protocol.tuning`)."""
    from voot.bench.protocol.layouts import check_protocol
    from voot.bench.protocol.select import selection_table
    from voot.bench.protocol.tuning import (
        seeds_text,
        selected_specs,
        tuning_note,
        tuning_selections,
    )
    from voot.bench.sweep.plan import summarize_plan_specs

    tuning_seeds = sorted({s.seed for s in tuning})
    tuning_layouts = sorted({s.layout for s in tuning if s.layout is not None})
    eval_layouts = sorted({s.layout for s in candidates if s.layout is not None})
    held_out = _layout_options(args).tuning is not None
    try:
        check_protocol(
            tuning_seeds,
            {s.seed for s in candidates},
            tuning_layouts if held_out else None,
            eval_layouts,
        )
    except ValueError as exc:
        raise C.CLIError(str(exc)) from None
    existing = C.existing_store(args.out)
    rows = existing.load(kind="plan", status="ok") if existing is not None else []
    selections = tuning_selections(tuning, rows)
    complete = existing is not None and not _pending(tuning, existing)
    if complete:
        evaluation = selected_specs(candidates, selections)
    else:  # the selection is not known yet: one setting per pair stands in for it
        evaluation = _one_setting_each(candidates)
    eval_seeds = seeds_text({s.seed for s in candidates})
    on_tuning = f"seeds {seeds_text(tuning_seeds)}"
    on_eval = f"seeds {eval_seeds}"
    if tuning_layouts:
        on_tuning += f" x layouts {seeds_text(tuning_layouts)}"
    if eval_layouts:
        on_eval += f" x layouts {seeds_text(eval_layouts)}"
    print(
        f"tuning: {len(tuning)} runs (every setting) on {on_tuning};"
        f" evaluation: {len(evaluation)} runs (the selected setting) on {on_eval}"
        f"{'' if complete else ', after the tuning runs'}{C.stored_note(args.out, tuning)}",
        file=sys.stderr,
    )
    if args.estimate:
        return _print_estimate(args, [*tuning, *evaluation])
    if args.dry_run:
        print("tuning runs:")
        print(summarize_plan_specs(tuning))
        print("evaluation runs (one setting per problem and planner):")
        print(summarize_plan_specs(evaluation))
        return 0
    store = C.open_store(args.out, C.compact_config(args) if args.compact else None)
    summary = _run_plan_specs(args, tuning, store)
    if summary.failed or _pending(tuning, store):
        print(
            "voot-bench: tuning runs failed or are missing; the evaluation waits for every"
            " tuning run (a selection on part of them would not be the protocol's)",
            file=sys.stderr,
        )
        return 1
    selections = tuning_selections(tuning, store.load(kind="plan", status="ok"))
    print(selection_table(selections, kind="plan"), file=sys.stderr)
    print(f"({tuning_note(tuning_seeds, tuning_layouts if held_out else ())})", file=sys.stderr)
    evaluation = selected_specs(candidates, selections)
    return 1 if _run_plan_specs(args, evaluation, store).failed else 0


@dataclass(frozen=True)
class LayoutOptions:
    """The layout seeds of ``--layout-seeds``, ``--tuning-layouts`` and ``--heldout``.

    ``evaluation`` and ``tuning`` are the layouts of the evaluation and tuning runs (None:
    no layout axis, no layout split); with ``heldout`` they come per problem from its
    held-out set (:func:`voot.bench.protocol.layouts.layout_set`).
    """

    evaluation: list[int] | None = None
    tuning: list[int] | None = None
    heldout: bool = False

    def groups(
        self, problems: Sequence[str], tuning: bool
    ) -> list[tuple[list[str], list[int] | None]]:
        """``(problems, layout seeds)`` pairs to build specs of, for the tuning runs
        (``tuning``) or the evaluation runs."""
        if not self.heldout:
            # without tuning layouts both phases run on the evaluation layouts (if any)
            both = self.evaluation if self.tuning is None else self.tuning
            return [(list(problems), both if tuning else self.evaluation)]
        from voot.bench.protocol.layouts import layout_set
        from voot.bench.protocol.problems import normalize_problem

        out: list[tuple[list[str], list[int] | None]] = []
        for name in problems:
            try:
                split = layout_set(normalize_problem(name))
            except ValueError as exc:
                raise C.CLIError(f"--heldout: {exc}") from None
            out.append(([name], list(split.training if tuning else split.heldout)))
        return out


def _layout_options(args: argparse.Namespace) -> LayoutOptions:
    """Parse ``--layout-seeds``, ``--tuning-layouts`` and ``--heldout`` (errors name the
    option)."""
    from voot.bench.protocol.layouts import HELDOUT_LAYOUTS, layouts_text

    # commands that share plan_tuned without the layout options (ablation) have none
    layout_seeds = getattr(args, "layout_seeds", None)
    tuning_layouts = getattr(args, "tuning_layouts", None)
    if getattr(args, "heldout", False):
        if layout_seeds is not None or tuning_layouts is not None:
            raise C.CLIError(
                "--heldout sets the layouts itself (each family's training and held-out"
                " layouts); give either --heldout or --tuning-layouts with --layout-seeds"
            )
        return LayoutOptions(evaluation=[], tuning=[], heldout=True)
    evaluation = (
        parse_layout_seeds(layout_seeds, "--layout-seeds") if layout_seeds is not None else None
    )
    tuning = (
        parse_layout_seeds(tuning_layouts, "--tuning-layouts")
        if tuning_layouts is not None
        else None
    )
    if tuning is not None and evaluation is None:
        raise C.CLIError(
            "--tuning-layouts needs the evaluation layouts: give --layout-seeds (e.g. the"
            f" held-out layouts {layouts_text(HELDOUT_LAYOUTS)}: --layout-seeds 0:20) or use"
            " --heldout"
        )
    return LayoutOptions(evaluation, tuning)


def parse_layout_seeds(values: Sequence[str], what: str) -> list[int]:
    """Layout seeds: one ``N`` (0 .. N-1) or ``START:STOP``, or a list of seeds and
    ranges (``3 7 9``, ``0:5,100``); a single layout L is ``L:L+1``."""
    items = C.split_list(values)
    if not items:
        raise C.CLIError(f"{what}: no layout seeds given")
    out = C.parse_range(items[0], what) if len(items) == 1 else C.parse_int_list(items, what)
    if min(out) < 0:
        raise C.CLIError(f"{what}: layout seeds must be >= 0, got {min(out)}")
    if max(out) > C.MAX_LAYOUT_SEED:
        raise C.CLIError(
            f"{what}: layout seeds must be integers in [0, {C.MAX_LAYOUT_SEED}], got {max(out)}"
        )
    return list(dict.fromkeys(out))


def _pending(specs: Sequence[PlanSpec], store: ResultStore) -> list[PlanSpec]:
    from voot.bench.sweep.engine import pending_specs

    return list(pending_specs(specs, store))


def _one_setting_each(specs: Sequence[PlanSpec]) -> list[PlanSpec]:
    """The specs of the first setting of every (problem, planner): stand-ins for the
    evaluation runs before the tuning selected their setting."""
    from voot.bench.protocol.estimate import pair_of

    first: dict[object, object] = {}
    out = []
    for s in specs:
        key = pair_of(s)
        if first.setdefault(key, s.params) == s.params:
            out.append(s)
    return out


def register(sub: Subparsers) -> None:
    """Add ``plan``."""
    from voot.bench.protocol import problems as P
    from voot.bench.sweep.engine import GRIDS

    p = sub.add_parser(
        "plan",
        help="run planners x problems x seeds (paper Figure 4; resumable, local or Ray)",
        description="Tree-search sweep: every planner (with its hyperparameter grid) on every"
        " problem and seed, one row per run with the best return after every simulation."
        " Defaults are the paper's per problem: the Shekel chain in 10-D and 20-D (10,000"
        " simulations, 20 seeds, six planners); kitchen 2,000 simulations and 20 seeds;"
        " conveyor 3,000 simulations and 50 seeds (five planners).",
    )
    p.add_argument(
        "--out", default="results/plan", help="result store directory (default: %(default)s)"
    )
    p.add_argument(
        "--problems",
        nargs="+",
        metavar="NAME",
        help=f"the chains {' '.join(P.CHAINS)}; {P.names_text()}; or any gymnasium id"
        f" with get_state/set_state (default: {' '.join(P.DEFAULT_PROBLEMS)})",
    )
    p.add_argument("--dims", nargs="+", metavar="D", help="chain dimensions (default: 10 20)")
    p.add_argument(
        "--planners",
        nargs="+",
        metavar="NAME",
        help="voot doot rand_doot pw_uct voronoi_pw hoot uniform_t, or the sampling-based"
        " cem mppi predictive_sampling random_shooting, or the RL baselines ppo ddpg"
        " (budget matched to a voot search, docs/rl.md), or an outside planner: an installed"
        " plug-in's name (entry point group voot.planners) or module:attribute"
        " (docs/planners.md) (default: the paper's)",
    )
    p.add_argument(
        "--seeds", default=None, help="N (seeds 0..N-1) or START:STOP (default: the paper's)"
    )
    p.add_argument(
        "--simulations", type=int, default=None, help="simulations per run (default: the paper's)"
    )
    p.add_argument(
        "--grid", choices=GRIDS, default="paper", help="hyperparameter grid (default: %(default)s)"
    )
    p.add_argument(
        "--set",
        nargs="+",
        metavar="NAME=VALUE",
        help="a planner parameter for every run (e.g. depth_limit=5 omega=0.3; VOO's best-cell"
        " sampler: sampler=gaussian, or sampler.sampler=uniform to name it explicitly)",
    )
    p.add_argument(
        "--horizon",
        type=int,
        default=None,
        help="one planning horizon H from the root for every planner: a tree's depth_limit"
        " (no root commitment), a sampling-based planner's horizon (for control tasks that do"
        " not end by themselves)",
    )
    p.add_argument(
        "--env-kwargs",
        nargs="+",
        metavar="NAME=VALUE",
        help="keywords of gymnasium.make for the environments (e.g. dim=3)",
    )
    C.add_backend_options(p)
    p.add_argument("--record", metavar="RUN.rrd", help="record each run's search with rerun")
    p.add_argument(
        "--tuning-seeds",
        metavar="START:STOP",
        help="tune first: run every setting of the grid on these seeds, select per problem"
        " and planner the best mean final return, then run only that setting on --seeds"
        " (which must be disjoint); resumable at any point",
    )
    p.add_argument(
        "--layout-seeds",
        nargs="+",
        metavar="SEEDS",
        help="a layout axis of a generated family (an env taking layout_seed, e.g."
        " voot/KitchenClearing-v2): every run once per layout seed, N (0..N-1), START:STOP"
        " or a list (3 7 9); with it, --seeds defaults to one seed (0) per layout",
    )
    p.add_argument(
        "--tuning-layouts",
        nargs="+",
        metavar="SEEDS",
        help="the held-out protocol: tune every setting on these layouts (x --tuning-seeds,"
        " default: --seeds), select per family and planner the best mean final return"
        " pooled over them, then run that setting on --layout-seeds (which must be"
        " disjoint: no tuning on the test set); resumable at any point",
    )
    p.add_argument(
        "--heldout",
        action="store_true",
        help="the held-out protocol on each family's fixed layout sets: tune on its"
        " training layouts, evaluate on its held-out layouts (voot.bench.protocol.layouts:"
        " training 1000-1019, held-out 0-19)",
    )
    C.add_estimate_options(
        p,
        estimate="print the estimated CPU-hours of the runs not yet in --out (cost per"
        " simulation from the store's rows, else a short probe run) and exit",
    )
    C.add_run_options(p, dry_run="list the runs per problem and exit")
    C.add_compact_store_options(
        p,
        compact="create --out as a compact store (step curves exact, cost curves at reduced"
        " resolution; kept in its header, so later runs into it are compact too)",
    )
    p.set_defaults(func=cmd_plan)
