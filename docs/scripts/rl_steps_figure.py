"""The RL first look against simulator calls: best return per seed, tree and RL alike.

``python docs/scripts/rl_steps_figure.py docs/data/plan-rl-first-look docs/figures/rl_first_look_calls.png``

A tree row's x is its ``calls_curve`` (executed steps plus pre-checks after each
simulation), an RL row's its env steps (``best_by_step``, the best of the finished
episodes, held to the end of the budget): the same count of simulator calls.
"""

from __future__ import annotations

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from voot.bench.store.result_store import ResultStore

COLOURS = {"voot": "tab:blue", "ppo": "tab:orange", "ddpg": "tab:green"}


def main(store_dir: str, out: str) -> None:
    rows = [r for r in ResultStore(store_dir, create=False).iter_rows() if r.get("status") == "ok"]
    problems = sorted({r["problem_label"] for r in rows})
    fig, axes = plt.subplots(1, len(problems), figsize=(6 * len(problems), 4), squeeze=False)
    for ax, problem in zip(axes[0], problems, strict=True):
        seen: set[str] = set()
        for r in sorted(rows, key=lambda r: (r["config"]["planner"], r["config"]["seed"])):
            if r["problem_label"] != problem:
                continue
            planner = r["config"]["planner"]
            if "best_by_step" in r:
                pairs = r["best_by_step"]
                xs = [s for s, _ in pairs] + [r["rl_steps"]]
                ys = [b for _, b in pairs] + [pairs[-1][1]]
            else:
                xs, ys = r["calls_curve"], r["best_so_far"]
            label = None if planner in seen else planner
            seen.add(planner)
            ax.step(xs, ys, where="post", color=COLOURS.get(planner), alpha=0.8, label=label)
        ax.set_title(f"{problem}: best return, one line per seed")
        ax.set_xlabel("simulator calls (env steps; tree: steps + pre-checks)")
        ax.set_ylabel("best return")
        ax.grid(alpha=0.3)
        ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
