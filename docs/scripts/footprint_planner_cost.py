"""Where a tree planner's CPU goes with the exact footprint: one search, every exact query timed.

Runs one ``voot-bench plan`` search (VOOT by default) on ``voot/ConveyorPacking-v1`` with
``base_model="footprint"`` (and any other env keywords), with the exact-footprint
option's settings given here (:class:`~voot.envs.motion.footprint.FootprintConfig`:
``--static-cache``, ``--scene-cache``, ``--label-after``; unset: the option's defaults;
``--heuristic``: the env keyword ``footprint_heuristic``; ``--labelled-proof``: the
connectivity proof by scipy's labelling, the reference of the compiled runs), and prints the process's CPU
seconds, the exact queries' count, total and median CPU time, how many found a path and how many reached the connectivity
proof (``label_after``) with its total time, and the slowest queries. Random rollouts
(``voot-bench measure footprint-speed``) meet other queries than a tree search, which
samples near its best actions and revisits every depth; this measures the latter.

The options other than ``--heuristic`` change the time, never an answer, so the search
takes the same steps and makes the same queries under each (the query count says so).

Run from the repository root (a minute or two per run)::

    python docs/scripts/footprint_planner_cost.py --simulations 40
    python docs/scripts/footprint_planner_cost.py --simulations 150 --compare-geodesic \\
        --env-kwargs big_box_ban=true rooms=authors
"""

from __future__ import annotations

import argparse
import statistics
import tempfile
import time
from dataclasses import fields, replace
from typing import Any

from voot.envs.motion.footprint import FootprintConfig
from voot.envs.motion.footprint import search as FS
from voot.envs.motion.footprint.components import connected_labelled


def _set_defaults(overrides: dict[str, Any]) -> None:
    """Make ``FootprintConfig()`` (what ``base_model="footprint"`` builds) take ``overrides``."""
    defaults = list(FootprintConfig.__init__.__defaults__ or ())
    names = [f.name for f in fields(FootprintConfig)]
    for name, value in overrides.items():
        defaults[names.index(name)] = value
    FootprintConfig.__init__.__defaults__ = tuple(defaults)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--planner", default="voot")
    parser.add_argument("--simulations", type=int, default=40)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--env-kwargs", nargs="*", default=[], metavar="KEY=VALUE")
    parser.add_argument(
        "--set",
        nargs="*",
        default=[],
        metavar="NAME=VALUE",
        help="planner parameters (voot-bench plan --set)",
    )
    parser.add_argument("--static-cache", type=int, default=None)
    parser.add_argument("--scene-cache", type=int, default=None)
    parser.add_argument("--label-after", type=int, default=None)
    parser.add_argument("--heuristic", choices=("euclidean", "geodesic"), default=None)
    parser.add_argument(
        "--labelled-proof",
        action="store_true",
        help="prove connectivity by labelling (scipy) instead of the compiled runs "
        "(components.connected_labelled: the same answers, the reference's time)",
    )
    parser.add_argument(
        "--compare-geodesic",
        action="store_true",
        help="ask every query again of a twin search with heuristic='geodesic' and time it",
    )
    args = parser.parse_args()
    overrides = {
        name: value
        for name, value in (
            ("static_cache_size", args.static_cache),
            ("scene_cache_size", args.scene_cache),
            ("label_after", args.label_after),
        )
        if value is not None
    }
    _set_defaults(overrides)
    # the heuristic as the env sets it (ConveyorConfig.footprint_heuristic)
    heuristic = [f"footprint_heuristic={args.heuristic}"] if args.heuristic else []
    print(FootprintConfig())

    rows: list[dict[str, Any]] = []
    plan, connected = FS.FootprintSearch._plan, FS.FootprintSearch._connected
    if args.labelled_proof:

        def connected(self: Any, si: int, gi: int, free: Any) -> bool:
            return connected_labelled(free, si, gi)

    label: dict[str, float] = {}

    def timed_connected(self: Any, *a: Any) -> bool:
        t0 = time.process_time()
        out = connected(self, *a)
        label["t"] = time.process_time() - t0
        return out

    twins: dict[int, Any] = {}
    # the queries asked before in this process (the same search, ends, footprint, boxes
    # and disc radius: the same answer, as every answer is a function of these)
    asked: set[tuple[Any, ...]] = set()

    def timed_plan(self: Any, *a: Any) -> Any:
        if getattr(self, "is_twin", False):
            return plan(self, *a)
        label.clear()
        t0 = time.process_time()
        out = plan(self, *a)
        hub = a[4] if len(a) > 4 else None
        key = (id(self), *a[:4], getattr(hub, "_radius", None))
        row = {"t": time.process_time() - t0, "found": out is not None,
               "expansions": self.last_expansions, "label": label.get("t"),
               "repeat": key in asked}  # fmt: skip
        asked.add(key)
        if args.compare_geodesic:
            twin = twins.get(id(self))
            if twin is None:
                config = replace(self.config, heuristic="geodesic")
                twin = FS.FootprintSearch(self.workspace, self.static_obstacles, config,
                                          self.rotation_weight, self.tolerance)  # fmt: skip
                twin.is_twin = True
                twins[id(self)] = twin
            t0 = time.process_time()
            row["twin_found"] = plan(twin, *a) is not None
            row["twin_t"] = time.process_time() - t0
        rows.append(row)
        return out

    FS.FootprintSearch._plan = timed_plan  # type: ignore[method-assign]
    FS.FootprintSearch._connected = timed_connected  # type: ignore[method-assign]
    from voot.bench.cli.main import main as bench

    t0 = time.process_time()
    with tempfile.TemporaryDirectory() as out:
        bench(["plan", "--out", out, "--problems", "conveyor_v1", "--planners", args.planner,
               "--seeds", f"{args.seed}:{args.seed + 1}", "--simulations", str(args.simulations),
               *(["--set", *args.set] if args.set else []),
               "--grid", "default", "--env-kwargs", "base_model=footprint", *heuristic,
               *args.env_kwargs,
               "--workers", "1", "--backend", "serial", "--no-progress"])  # fmt: skip
    total = time.process_time() - t0
    times = sorted(r["t"] for r in rows)
    labelled = [r["label"] for r in rows if r["label"] is not None]
    print(
        f"{args.planner}, {args.simulations} simulations: process CPU {total:.1f} s; "
        f"{len(rows)} exact queries, {sum(times):.2f} s, median "
        f"{statistics.median(times) * 1000 if times else float('nan'):.1f} ms, "
        f"expansions: median {statistics.median(r['expansions'] for r in rows) if rows else 0:.0f}, "
        f"total {sum(r['expansions'] for r in rows)}; "
        f"{sum(r['found'] for r in rows)} found a path; {len(labelled)} reached the "
        f"connectivity proof ({sum(labelled):.2f} s in it); "
        f"{sum(r['repeat'] for r in rows)} asked before in this process "
        f"({sum(r['t'] for r in rows if r['repeat']):.2f} s in them)"
    )
    if args.compare_geodesic:
        twin_times = [r["twin_t"] for r in rows]
        print(
            f"the same queries with heuristic='geodesic': {sum(twin_times):.2f} s, median "
            f"{statistics.median(twin_times) * 1000 if rows else float('nan'):.1f} ms; "
            f"'a path exists' differs in {sum(r['found'] != r['twin_found'] for r in rows)}"
        )
    for r in sorted(rows, key=lambda r: -r["t"])[:5]:
        print(f"  {r['t'] * 1000:.0f} ms, {r['expansions']} expansions, found {r['found']}")


if __name__ == "__main__":
    main()
