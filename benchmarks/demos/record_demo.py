"""``voot-bench record-demo``: recordings, Figure-5 panels and a GIF on the tiny demo problem.

The demo problem is :class:`voot.envs.pick_place_demo.DemoPickPlace` (a walled room,
one box); :func:`record_demo` records planners on it with :func:`voot.record.record_plan`.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from voot.envs.pick_place_demo import DEMO_VIEW, DemoPickPlace


def record_demo(
    out: str | Path = ".",
    simulations: int = 300,
    seed: int = 0,
    planners: Sequence[str] = ("voot", "pw_uct"),
    watch: str = "best:place",
    video: bool = True,
) -> None:
    """Record ``planners`` on the demo, draw their Figure-5 panels and a GIF of VOOT's plan.

    Writes ``demo_<planner>.rrd`` per planner, ``demo_figure5.png`` (the placements of
    the node ``watch``: ``place``, the first place node, the paper's Figure 5, or
    ``best:place``, the place node of the best plan; one panel per planner, same seed) and,
    with ``video``, ``demo_voot.gif`` (VOOT's best plan, rendered headless) into ``out``.
    """
    from voot.record.config import RecorderConfig
    from voot.record.figure5 import samples_figure
    from voot.record.recorder import record_plan, watch_name

    config = RecorderConfig(watch=tuple(dict.fromkeys(("root", "place", watch))))

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    paths = {}
    results = {}
    for planner in planners:
        path = out / f"demo_{planner}.rrd"
        res = record_plan(DemoPickPlace(), path, planner, simulations, seed, config=config)
        paths[planner.upper().replace("_", "-")] = path
        results[planner] = res
        print(
            f"{planner}: best return {res.best_return:.3f}, plan of {len(res.actions)} actions,"
            f" {res.n_nodes} nodes -> {path}"
        )
    entity = f"scene/samples/{watch_name(watch)}/placements"
    try:
        fig = samples_figure(paths, out / "demo_figure5.png", entity, xlim=(-3, 3), ylim=(-3, 3))
        print(f"figure -> {fig}")
    except ValueError as exc:  # a planner reached no place node: too few simulations
        print(f"no figure: {exc}")
    if video and "voot" in results:
        from voot.record.video import write_plan_video

        gif = write_plan_video(
            out / "demo_voot.gif",
            DemoPickPlace(),
            actions=list(results["voot"].actions),
            width=360,
            height=270,
            fps=10,
            interpolate=6,
            hold_last=10,
            view=DEMO_VIEW,
        )
        print(f"video -> {gif}")
