"""The diagnosis of VOOT's stall on the kitchen: where it commits and why.

Re-runs (traced, bit-identical to the stored rows) the evaluation runs of VOOT and PW-UCT
on KitchenClearing-v1 seeds 0-19 with the settings the protocol selected on the tuning
seeds (docs/data/protocol-v1), and prints

* per seed, the last commitment and the draws at that root afterwards, by stage and cause
  (:func:`voot.bench.protocol.stall.stall_table`);
* over all commitments, the evidence they were made on: visits of the root that was left,
  children tied at the chosen Q, and the share of commitments into a dead end (a root that
  never gets a feasible action);

and writes them between the ``<!-- ablation-v1:stall -->`` markers of
``docs/results-planning.md``, and draws ``docs/figures/ablation/stall.png``:

    python docs/scripts/ablation_stall.py
"""

from __future__ import annotations

import contextlib
import importlib.util
import io
import sys
from pathlib import Path

import numpy as np

from voot.bench.protocol.stall import commitments, stall_table, summarize, trace_search
from voot.bench.sweep.plan import PlanSpec

KITCHEN = "voot/KitchenClearing-v1"
#: The settings selected on tuning seeds 1000-1004 (docs/results-planning.md).
SELECTED = {
    "voot": (("omega", 0.3), ("reevaluations", 5)),
    "pw_uct": (("pw_k", 1.0), ("ucb_c", 1.0)),
}
SEEDS = range(20)


def main() -> None:
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        measure()
    spec = importlib.util.spec_from_file_location(
        "ablation_docs", Path(__file__).with_name("ablation_docs.py")
    )
    assert spec is not None and spec.loader is not None
    docs = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(docs)
    page = docs.PAGE.read_text()
    docs.PAGE.write_text(docs.replace(page, "stall", out.getvalue().strip() + "\n"))
    print(out.getvalue())


def measure() -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    evidence = {}
    for planner, params in SELECTED.items():
        summaries, events = [], []
        exploiting = tied_draws = 0
        for seed in SEEDS:
            trace, mcts = trace_search(PlanSpec(KITCHEN, None, (), planner, params, 2000, seed))
            summaries.append(summarize(seed, trace, mcts))
            exploiting += trace.exploiting_draws
            tied_draws += trace.tied_best_draws
            events += commitments(trace, mcts)
            print(f"{planner} seed {seed} done", file=sys.stderr)
        evidence[planner] = events
        print(f"\n##### {planner}: the last root of each search\n")
        print(stall_table(summaries))
        visits = np.array([e.parent_visits for e in events])
        tied = np.array([e.tied_children == e.feasible_children for e in events])
        dead = np.array([e.dead_end for e in events])
        print(
            f"\n{planner}: {len(events)} commitments on {len(SEEDS)} seeds; visits of the"
            f" root left: median {np.median(visits):.0f} (quartiles {np.quantile(visits, 0.25):.0f}"
            f"-{np.quantile(visits, 0.75):.0f}); every live child tied at the chosen Q:"
            f" {tied.sum()} ({100 * tied.mean():.0f}%); into a dead end: {dead.sum()}"
            f" ({100 * dead.mean():.0f}%)"
        )
        if planner == "voot":
            print(
                f"\nvoot: {exploiting} new actions at VOO nodes with a feasible action; the best"
                f" value tied between several points at {tied_draws} of them"
            )
    fig, ax = plt.subplots(1, 2, figsize=(10, 3.6))
    for planner, events in evidence.items():
        v = [e.parent_visits for e in events]
        ax[0].hist(v, bins=np.geomspace(5, 5000, 30), alpha=0.6, label=planner)
        d = [e.depth for e in events if e.dead_end]
        ax[1].hist(d, bins=np.arange(0.5, 15.5), alpha=0.6, label=planner)
    ax[0].set_xscale("log")
    ax[0].set_xlabel("visits of the root it left, at each commitment")
    ax[0].set_ylabel("commitments (20 seeds)")
    ax[1].set_xlabel("depth of a commitment into a dead end")
    ax[1].set_ylabel("commitments")
    for a in ax:
        a.legend()
    fig.tight_layout()
    fig.savefig("docs/figures/ablation/stall.png", dpi=120)


if __name__ == "__main__":
    main()
