"""The demos: ``demo`` (VOOT clearing the kitchen, with a rerun recording and a GIF; on
a generated kitchen with ``--env kitchen_v2 --layout-seed S --difficulty D``),
``record-demo`` (recordings, Figure-5 panels and a GIF on the tiny pick-and-place demo),
``figure5`` (the paper's Figure 5 on the kitchen), ``demo-voo`` (VOO on a test function
with the paper's budget) and ``env-figures`` (pictures of the two scenes, as in the
docs)."""

from __future__ import annotations

import argparse
import sys
import time
from typing import TYPE_CHECKING

from voot.bench.cli.common import CLIError, check_output
from voot.bench.cli.types import seed_argument

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers

#: ``--difficulty`` of ``demo`` (:data:`voot.envs.kitchen.generated.layout.DIFFICULTIES`; written
#: out so that ``voot-bench --help`` does not import the environments).
DIFFICULTY_CHOICES = ("easy", "medium", "hard")
#: Defaults of ``--layout-seed`` and ``--difficulty`` as the help states them
#: (:data:`voot.bench.demos.kitchen_demo.DEFAULT_LAYOUT_SEED`, ``DEFAULT_DIFFICULTY``).
DEFAULT_LAYOUT_SEED = 0
DEFAULT_DIFFICULTY = "easy"
#: The kitchen of the paper's protocol: the default ``--env`` of ``demo`` and ``figure5``.
PAPER_KITCHEN = "kitchen_v1"


def cmd_demo(args: argparse.Namespace) -> int:
    """VOOT on the kitchen: prints obstacles cleared, writes ``.rrd``, ``.gif``, ``.json``."""
    from voot.bench.demos import kitchen_demo
    from voot.bench.protocol.problems import normalize_problem

    check_output(args.out, "--out", folder=True)
    sims = kitchen_demo.DEFAULT_SIMULATIONS if args.simulations is None else args.simulations
    seed = kitchen_demo.DEFAULT_SEED if args.seed is None else args.seed
    try:
        env_id = normalize_problem(args.env)
        if not kitchen_demo.is_generated(env_id) and (
            args.layout_seed is not None or args.difficulty is not None
        ):
            given = [
                flag
                for flag, value in (
                    ("--layout-seed", args.layout_seed),
                    ("--difficulty", args.difficulty),
                )
                if value is not None
            ]
            verb = "choose" if len(given) > 1 else "chooses"
            raise CLIError(
                f"{' and '.join(given)} {verb} a generated kitchen; --env {args.env} ({env_id})"
                " is the paper's fixed instance: use --env generated_kitchen"
            )
        kitchen_demo.run(
            args.out,
            sims,
            seed,
            args.planner,
            video=not args.no_video,
            env_id=env_id,
            layout_seed=args.layout_seed,
            difficulty=args.difficulty,
        )
    except ValueError as exc:
        raise CLIError(str(exc)) from exc
    return 0


def cmd_record_demo(args: argparse.Namespace) -> int:
    """Record planners on the tiny demo (:func:`voot.bench.demos.record_demo.record_demo`)."""
    from voot.bench.demos.record_demo import record_demo

    check_output(args.out, "--out", folder=True)
    record_demo(
        args.out,
        args.simulations,
        args.seed,
        args.planners,
        watch=args.watch,
        video=not args.no_video,
    )
    return 0


def cmd_env_figures(args: argparse.Namespace) -> int:
    """Render the scenes' figures (:func:`voot.bench.demos.env_figures.render_all`)."""
    from pathlib import Path

    from voot.bench.demos import env_figures

    check_output(args.out_dir, "OUT_DIR", folder=True)
    env_figures.render_all(Path(args.out_dir))
    return 0


def cmd_figure5(args: argparse.Namespace) -> int:
    """Record the paper's Figure 5 on the kitchen and draw it (:mod:`voot.bench.demos.figure5`)."""
    from voot.bench.demos.figure5 import figure5
    from voot.bench.protocol.problems import normalize_problem

    if args.seed < 0:
        raise CLIError(f"--seed must be >= 0, got {args.seed}")
    check_output(args.out, "--out", folder=True)
    figure5(
        args.out,
        args.seed,
        planners=args.planners,
        visits=args.visits,
        max_simulations=args.max_simulations,
        env_id=normalize_problem(args.env),
        image=args.image,
    )
    return 0


def cmd_demo_voo(args: argparse.Namespace) -> int:
    from voot.bench.sweep.bbfo import RunSpec, check_functions, paper_budget, run_spec
    from voot.functions import get_function
    from voot.optim.registry import normalize_method

    function = check_functions([args.function])[0]
    method = normalize_method(args.method)
    if args.dim < 1:
        raise CLIError(f"--dim must be >= 1, got {args.dim}")
    budget = args.budget if args.budget is not None else paper_budget(function, args.dim)
    if budget < 1:
        raise CLIError(f"--budget must be >= 1, got {budget}")
    spec = RunSpec(function, args.dim, method, (), budget, args.seed)
    print(
        f"{method} on {function}-{args.dim}D, {budget} evaluations, seed {args.seed} ...",
        file=sys.stderr,
    )
    start = time.perf_counter()
    row = run_spec(spec)
    elapsed = time.perf_counter() - start
    if row["status"] != "ok":
        print(f"voot-bench: run failed: {row['error']}", file=sys.stderr)
        return 1
    best = float(row["best_so_far"][-1])
    optimum = get_function(function, args.dim).optimum_value
    print(
        f"{method} on {function}-{args.dim}D: {budget} evaluations in {elapsed:.1f} s (seed {args.seed})"
    )
    print(f"  best value found  {best:.6g}")
    if optimum is not None:
        print(f"  known optimum     {float(optimum):.6g}")
        print(f"  regret            {float(optimum) - best:.6g}")
    for k in (10, 100, 1000):
        if k < budget:
            print(f"  best after {k:>5}  {float(row['best_so_far'][k - 1]):.6g}")
    return 0


def register(sub: Subparsers) -> None:
    """Add ``demo``, ``record-demo``, ``figure5``, ``demo-voo`` and ``env-figures``."""
    from voot.bench.protocol import problems as P

    p = sub.add_parser(
        "demo",
        help="the README's main job: VOOT clearing the kitchen, with a rerun recording and a GIF",
    )
    p.add_argument("--out", default="kitchen_demo", help="output folder (default: kitchen_demo)")
    p.add_argument("--simulations", type=int, default=None, help="default: 1000")
    p.add_argument(
        "--seed", type=seed_argument, default=None, help="default: the documented demo seed"
    )
    p.add_argument("--planner", default="voot")
    p.add_argument("--no-video", action="store_true", help="skip the GIF")
    p.add_argument(
        "--env",
        default=PAPER_KITCHEN,
        help=f"{P.names_text('kitchen')} (default: %(default)s); a generated kitchen takes"
        " --layout-seed and --difficulty",
    )
    p.add_argument(
        "--layout-seed",
        type=seed_argument,
        default=None,
        help="kitchen_v2 only: the generated kitchen's layout seed (default: "
        f"{DEFAULT_LAYOUT_SEED})",
    )
    p.add_argument(
        "--difficulty",
        choices=DIFFICULTY_CHOICES,
        default=None,
        help=f"kitchen_v2 only: the generated kitchen's level (default: {DEFAULT_DIFFICULTY})",
    )
    p.set_defaults(func=cmd_demo)

    p = sub.add_parser(
        "record-demo",
        help="recordings, Figure-5 panels and a GIF on the tiny pick-and-place demo",
        description="Record planners on the demo, draw their Figure-5 panels and a GIF of"
        " VOOT's plan: demo_<planner>.rrd per planner, demo_figure5.png (the watched place"
        " node's placements, one panel per planner, same seed) and demo_voot.gif (VOOT's"
        " best plan, rendered headless).",
    )
    p.add_argument("--out", default=".", help="output folder")
    p.add_argument("--simulations", type=int, default=300)
    p.add_argument("--seed", type=seed_argument, default=0)
    p.add_argument("--planners", nargs="+", default=["voot", "pw_uct"])
    p.add_argument(
        "--watch",
        default="best:place",
        help="the node drawn in the figure: 'place' (the first place node, the paper's"
        " Figure 5) or 'best:place' (the place node of the best plan)",
    )
    p.add_argument("--no-video", action="store_true")
    p.set_defaults(func=cmd_record_demo)

    p = sub.add_parser(
        "figure5",
        help="the paper's Figure 5 on the kitchen: placements sampled at the first place node",
    )
    p.add_argument("--out", default="kitchen_demo", help="output folder (default: kitchen_demo)")
    p.add_argument("--seed", type=seed_argument, default=0)
    p.add_argument("--planners", nargs="+", default=["voot", "pw_uct"], metavar="NAME")
    p.add_argument("--visits", type=int, default=50, help="visits of the node (the paper's 50)")
    p.add_argument("--max-simulations", type=int, default=2000)
    p.add_argument(
        "--env",
        default=PAPER_KITCHEN,
        help=f"{P.names_text('kitchen', ('protocol', 'v0'))} (default: %(default)s)",
    )
    p.add_argument(
        "--image",
        default="kitchen_figure5.png",
        help="image file name in --out (default: %(default)s); its counts go beside it as .json",
    )
    p.set_defaults(func=cmd_figure5)

    p = sub.add_parser("demo-voo", help="VOO on Shekel-20D with the paper's budget")
    p.add_argument("--function", default="shekel")
    p.add_argument("--dim", type=int, default=20)
    p.add_argument("--method", default="voo")
    p.add_argument("--budget", type=int, default=None, help="evaluations (default: the paper's)")
    p.add_argument("--seed", type=seed_argument, default=0)
    p.set_defaults(func=cmd_demo_voo)

    p = sub.add_parser(
        "env-figures",
        help="render the environment figures of the docs",
        description="Render the kitchen and the storage rooms at the start and after the"
        " scripted solution, top-down and in perspective, and the robot holding a box"
        " (headless, MUJOCO_GL=egl).",
    )
    p.add_argument(
        "out_dir", nargs="?", default="docs/figures", help="folder of the figures (%(default)s)"
    )
    p.set_defaults(func=cmd_env_figures)
