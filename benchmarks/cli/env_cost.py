"""What the environments cost, under ``voot-bench measure``: ``env-speed`` (step costs and
sparsity of the robot domains, :mod:`voot.bench.measure.env_speed`), ``mesh-speed``
(the trimesh object meshes, per shape and per scene, cold and cached, and a grasp lookup,
:mod:`voot.bench.measure.mesh_speed`), ``footprint-speed`` (the base planner's
exact-footprint option, :mod:`voot.bench.measure.footprint_speed`) and
``domain-ablation`` (the conveyor's domain departures one at a time,
:mod:`voot.bench.protocol.domain_ablation`). All need the ``envs`` extra, imported only
when the command runs; every option and output path is checked before the work starts."""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path
from typing import TYPE_CHECKING

from voot.bench.cli.common import CLIError, check_output
from voot.bench.cli.types import seed_argument

if TYPE_CHECKING:
    from voot.bench.cli.common import Subparsers


def cmd_env_speed(args: argparse.Namespace) -> int:
    """Print the step costs and sparsity of the robot domains (:mod:`voot.bench.measure.env_speed`)."""
    from voot.bench.measure.env_speed import report, run

    if args.n < 1:
        raise CLIError("--n must be >= 1")
    print(report(run(args.n, args.seed)))
    return 0


def cmd_mesh_speed(args: argparse.Namespace) -> int:
    """Print the tables of :mod:`voot.bench.measure.mesh_speed`."""
    from voot.bench.measure import mesh_speed as S
    from voot.envs.assets.meshes import SHAPE_KINDS, ShapeSpec

    if args.repeats < 1 or args.calls < 1:
        raise CLIError("--repeats and --calls must be >= 1")
    kinds = args.kinds or list(SHAPE_KINDS)
    unknown = [k for k in kinds if k not in SHAPE_KINDS]
    if unknown:
        raise CLIError(f"unknown kind {unknown[0]!r}; valid kinds: {', '.join(SHAPE_KINDS)}")
    specs = [ShapeSpec(k, S.SIZES[k]) for k in kinds]
    clock = time.process_time if args.cpu else time.perf_counter
    what = "CPU time" if args.cpu else "wall time"
    print(f"per shape (meshes + grasp table), {what}, median of {args.repeats}")
    print("| kind | size (m) | triangles | parts | STL kB | cold ms | disk ms | memory ms |")
    print("| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: |")
    for spec, t in zip(specs, S.time_shapes(specs, args.repeats, clock), strict=True):
        size = " x ".join(f"{v:g}" for v in spec.size)
        print(
            f"| {spec.kind} | {size} | {t['triangles']:.0f} | {t['parts']:.0f} |"
            f" {t['bytes'] / 1000:.0f} | {1000 * t['cold']:.1f} | {1000 * t['disk']:.2f} |"
            f" {1000 * t['memory']:.3f} |",
            flush=True,
        )
    if not args.no_scene:
        t = S.time_scene(S.SCENE, args.repeats, clock)
        print(
            f"\nscene of {len(S.SCENE)} objects + robot, compiled, {what}, median of {args.repeats}"
        )
        print("| cold ms | disk cache ms | memory ms | robot alone ms |")
        print("| ---: | ---: | ---: | ---: |")
        print(
            f"| {1000 * t['cold']:.0f} | {1000 * t['disk']:.1f} | {1000 * t['memory']:.1f} |"
            f" {1000 * t['robot_only']:.1f} |",
            flush=True,
        )
    print(f"\ngrasp lookup, us per call, {what} ({args.calls} calls)")
    print("| kind | mesh_side_grasp | side_grasp | hits |")
    print("| --- | ---: | ---: | ---: |")
    for spec in specs:
        t = S.time_lookup(spec, args.calls, clock)
        print(
            f"| {spec.kind} | {t['mesh_us']:.1f} | {t['side_us']:.1f} |"
            f" {100 * t['hit_share']:.0f} % |",
            flush=True,
        )
    return 0


def cmd_footprint_speed(args: argparse.Namespace) -> int:
    """Print :mod:`voot.bench.measure.footprint_speed`'s query times and cost ratio."""
    from voot.bench.measure.footprint_speed import report, run

    if args.rollouts < 1:
        raise CLIError(f"--rollouts must be >= 1, got {args.rollouts}")
    if args.label_after is not None and args.label_after < 0:
        raise CLIError(f"--label-after must be >= 0 (0: never), got {args.label_after}")
    if args.repeats < 1:
        raise CLIError(f"--repeats must be >= 1, got {args.repeats}")
    r = run(args.rollouts, args.seed, args.coarse_first, args.engine, args.label_after,
            args.heuristic, args.repeats)  # fmt: skip
    print(report(r))
    return 0


def cmd_domain_ablation(args: argparse.Namespace) -> int:
    """Run (or with ``--table`` redraw) :mod:`voot.bench.protocol.domain_ablation`."""
    from voot.bench.protocol import domain_ablation as D

    if args.table is not None:
        try:
            store = json.loads(Path(args.table).read_text(encoding="utf-8"))
            text = D.table(store)
        except (OSError, ValueError, KeyError, TypeError, AttributeError) as exc:
            raise CLIError(
                f"--table {args.table}: not a readable domain-ablation store ({exc})"
            ) from None
        print(text)
        return 0
    for name in ("draws", "executions", "rollouts"):
        if getattr(args, name) < 1:
            raise CLIError(f"--{name} must be >= 1, got {getattr(args, name)}")
    known = D.switches_of(args.domain)
    switches = tuple(args.switches or known)
    unknown = [s for s in switches if s not in known]
    if unknown:
        raise CLIError(
            f"unknown switch {unknown[0]!r} of the {args.domain}; valid switches:"
            f" {', '.join(known)}"
        )
    bounds: dict[str, int] = {}
    for item in args.executions_for or ():
        name, _, value = item.partition("=")
        if name not in known:
            raise CLIError(
                f"--executions-for {item!r}: unknown switch {name!r}; valid switches:"
                f" {', '.join(known)}"
            )
        try:
            bounds[name] = int(value)
        except ValueError:
            bounds[name] = 0
        if bounds[name] < 1:
            raise CLIError(f"--executions-for {item!r}: give SWITCH=N with N >= 1")
    check_output(args.out, "--out")
    store = D.run(
        switches,
        args.draws,
        args.executions,
        args.rollouts,
        args.seed,
        executions_for=bounds,
        domain=args.domain,
    )
    if args.out is not None:
        Path(args.out).write_text(json.dumps(store, indent=1) + "\n")
    print(D.table(store))
    return 0


def register(sub: Subparsers) -> None:
    """Add ``env-speed``, ``mesh-speed``, ``footprint-speed`` and ``domain-ablation``."""
    p = sub.add_parser(
        "env-speed",
        help="step costs and sparsity of the robot domains",
        description="Speed benchmark of the two environments (a command, not a test).",
    )
    p.add_argument("--n", type=int, default=1000, help="random actions per operator (default 1000)")
    p.add_argument("--seed", type=seed_argument, default=0, help="seed of the random actions")
    p.set_defaults(func=cmd_env_speed)

    p = sub.add_parser(
        "mesh-speed",
        help="cost of the trimesh object meshes: per shape and per scene, cold and cached,"
        " and of a grasp lookup",
        description="Builds each kind's mesh, convex parts and grasp table in a temporary"
        " cache folder (cold), reads them back (disk) and again (memory); compiles a scene"
        " of ten objects the same three ways; times mesh_side_grasp against side_grasp.",
    )
    p.add_argument(
        "--kinds", nargs="*", default=None, help="shape kinds (default: all of SHAPE_KINDS)"
    )
    p.add_argument("--repeats", type=int, default=3, help="median of (default: %(default)s)")
    p.add_argument(
        "--calls", type=int, default=20000, help="lookups timed per kind (default: %(default)s)"
    )
    p.add_argument("--no-scene", action="store_true", help="skip the scene measurement")
    p.add_argument(
        "--cpu",
        action="store_true",
        help="time with this process's CPU time instead of the wall clock (less inflated"
        " on a machine shared with other jobs; file reads waiting on the disk not counted)",
    )
    p.set_defaults(func=cmd_mesh_speed)

    p = sub.add_parser(
        "footprint-speed",
        help="cost of the base planner's exact-footprint option on the conveyor",
        description="Median exact lattice query and the conveyor simulation CPU-cost ratio"
        " of the exact-footprint option against the disc, measured in the same run.",
    )
    p.add_argument("--rollouts", type=int, default=20, help="random rollouts (default 20)")
    p.add_argument("--seed", type=seed_argument, default=0, help="seed of the random actions")
    p.add_argument(
        "--coarse-first",
        action="store_true",
        help="FootprintConfig(coarse_first=True): the lattice of twice the step first",
    )
    p.add_argument(
        "--engine",
        choices=("compiled", "python"),
        default="compiled",
        help="FootprintConfig.engine: the A* loop compiled with numba (default) or the"
        " pure-Python reference (the same paths)",
    )
    p.add_argument(
        "--label-after",
        type=int,
        default=None,
        help="FootprintConfig.label_after: expansions before the connectivity proof"
        " (default: the option's; the answers do not depend on it)",
    )
    p.add_argument(
        "--heuristic",
        choices=("euclidean", "geodesic"),
        default="euclidean",
        help="FootprintConfig.heuristic: A*'s position term (the same 'a path exists'"
        " answers, other paths)",
    )
    p.add_argument(
        "--repeats",
        type=int,
        default=1,
        help="replay the steps this many times with fresh environments and keep the least"
        " times (on a shared machine: the least disturbed; default 1)",
    )
    p.set_defaults(func=cmd_footprint_speed)

    p = sub.add_parser(
        "domain-ablation",
        help="the domains' departures switched one at a time: planner-agnostic statistics",
        description="Pre-check and execution rates by node, random-rollout success and the"
        " scripted solution, on ConveyorPacking-v1 (or KitchenClearing-v1) with each"
        " domain switch.",
    )
    p.add_argument(
        "--domain",
        choices=("conveyor", "kitchen"),
        default="conveyor",
        help="ConveyorPacking-v1 (default) or KitchenClearing-v1",
    )
    p.add_argument("--switches", nargs="*", default=None, help="default: every switch")
    p.add_argument("--draws", type=int, default=2000, help="uniform draws per node")
    p.add_argument("--executions", type=int, default=40, help="executed passes per node")
    p.add_argument(
        "--executions-for",
        nargs="*",
        default=None,
        metavar="SWITCH=N",
        help="a switch's own bound on the executed passes per node (for the slow ones)",
    )
    p.add_argument("--rollouts", type=int, default=5, help="random rollouts")
    p.add_argument("--seed", type=seed_argument, default=0)
    p.add_argument("--out", default=None, help="write the store (JSON) here")
    p.add_argument("--table", default=None, help="only redraw the table of this store")
    p.set_defaults(func=cmd_domain_ablation)
