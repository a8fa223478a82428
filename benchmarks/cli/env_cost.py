"""What the environments cost, under ``voot-bench measure``: ``env-speed`` (step costs and
sparsity of the robot domains, :mod:`voot.bench.measure.env_speed`) and ``mesh-speed``
(the trimesh object meshes, per shape and per scene, cold and cached, and a grasp lookup,
:mod:`voot.bench.measure.mesh_speed`). Both need the ``envs`` extra, imported only when
the command runs."""

from __future__ import annotations

import argparse
import time
from typing import TYPE_CHECKING

from voot.bench.cli.common import CLIError
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


def register(sub: Subparsers) -> None:
    """Add ``env-speed`` and ``mesh-speed``."""
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
