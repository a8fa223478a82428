"""When each planner's best plan last improved, on the v1 protocol's evaluation seeds.

Reads the committed store ``docs/data/protocol-v1`` (settings selected on the tuning
seeds 1000-1004) and prints, per problem and planner, the median simulation of the last
improvement of the best return and the executed steps per simulation after it: a search
whose later simulations each execute one failing step has stalled at its committed root.

    python docs/scripts/protocol_v1_stalls.py
"""

from __future__ import annotations

import numpy as np

from voot.bench.report.plan_runs import plan_data
from voot.bench.store.result_store import ResultStore


def main() -> None:
    rows = ResultStore("docs/data/protocol-v1", create=False).load(kind="plan")
    data = plan_data(rows, tuning_seeds=range(1000, 1005))
    print(
        "| problem | planner | seeds | last improvement (median simulation) | seeds still improving in the last quarter |"
    )
    print("| --- | --- | ---: | ---: | ---: |")
    for d in data:
        returns = d.returns
        last = []
        for curve in returns:
            changes = np.flatnonzero(np.diff(curve) != 0)
            last.append(int(changes[-1]) + 2 if changes.size else 1)
        late = sum(v > 0.75 * d.simulations for v in last)
        print(
            f"| {d.problem} | {d.planner} | {d.n_seeds} | {int(np.median(last))} |"
            f" {late}/{d.n_seeds} |"
        )


if __name__ == "__main__":
    main()
