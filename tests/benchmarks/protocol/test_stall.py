"""Tests of voot.bench.protocol.stall: a traced search is the same search, and its summary."""

from __future__ import annotations

from voot.bench.protocol.stall import stall_table, summarize, trace_search
from voot.bench.sweep.plan import PlanSpec, run_plan_spec

SPEC = PlanSpec(
    "voot/KitchenClearing-v1", None, (), "voot", (("omega", 0.3), ("reevaluations", 5)), 120, 0
)


def test_a_traced_search_is_the_stored_run_and_every_draw_is_recorded() -> None:
    trace, mcts = trace_search(SPEC)
    row = run_plan_spec(SPEC)
    assert trace.curve == row["best_so_far"]  # tracing changes nothing
    stages = [d.stage for d in trace.draws]
    assert stages.count("precheck") + 0 <= mcts.n_feasibility_checks
    executed = sum(s != "precheck" for s in stages)
    assert executed == mcts.n_steps == row["n_steps"]
    assert all(d.cause for d in trace.draws if d.stage != "feasible")
    assert trace.roots[0][:3] == (0, 0, 0)
    depths = [r[2] for r in trace.roots]
    assert len(trace.roots) >= 2 and max(depths) >= 1  # it committed at least once


def test_the_summary_counts_the_draws_at_the_last_root() -> None:
    trace, mcts = trace_search(SPEC)
    s = summarize(0, trace, mcts)
    sim, root_id, depth, _ = trace.roots[-1]
    at_root = [d for d in trace.draws if d.node == root_id and d.simulation >= sim]
    assert s.draws == len(at_root)
    assert sum(s.precheck.values()) + sum(s.execution.values()) + s.feasible == s.draws
    assert s.root_depth == depth and s.committed_at == sim + 1
    assert 1 <= s.last_improvement <= SPEC.simulations
    text = stall_table([s, s])
    assert text.count("\n| 0 |") == 2 and "| all |" in text
