"""Hashes of a fixed set of voot's outputs, to prove that a restructuring preserves behaviour.

    python tools/behaviour_hashes.py record tools/behaviour_hashes.json   # before
    python tools/behaviour_hashes.py compare tools/behaviour_hashes.json  # after
    python tools/behaviour_hashes.py bbfo-digest voo    # one black-box run's hash

The v1 fingerprints of every planner (a short run of each tree and sampling planner on
both v1 domains, :func:`v1_fingerprints`) are pinned in ``tools/v1_fingerprints.json``;
``record`` writes them and ``compare`` checks them on a line of their own. The RL
planners (ppo, ddpg) are pinned in ``tools/v1_rl_fingerprints.json`` where torch is
installed (the ``rl`` extra; :func:`v1_rl_fingerprints`): ``record`` and ``compare`` include
them there, and

    python tools/behaviour_hashes.py record-rl    # the RL fingerprints alone
    python tools/behaviour_hashes.py compare-rl

CMA-ES is pinned by its curve (``tools/behaviour_curves.json``, compared within a relative
tolerance, see :data:`CMAES_RTOL`): its last bits depend on the CPU's BLAS kernel.

Covers: black-box sweep runs (VOO, DOO, CMA-ES) and a whole bbfo sweep through the store,
plan-sweep runs on a chain and on both kitchen versions and a whole plan sweep, a
root-parallel search, the kitchen demo's JSON (timings dropped) and
its recording's entity list. Every output is deterministic; timings are left out.
"""

from __future__ import annotations

import hashlib
import json
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from voot.bench.sweep.planners import PLAN_PLANNERS, RL_PLANNERS

TIMING_KEYS = {
    "wall_time",
    "elapsed",
    "cpu_elapsed",
    "search_time",
    "finished_at",
    "versions",
    "created",
}


def _digest(value: Any) -> str:
    """A stable hash of nested plain values and arrays (floats by their exact bits)."""

    def plain(v: Any) -> Any:
        if isinstance(v, np.ndarray):
            return {"array": v.dtype.str, "shape": list(v.shape), "hex": v.tobytes().hex()}
        if isinstance(v, float):
            return {"float": v.hex()}
        if isinstance(v, dict):
            return {str(k): plain(x) for k, x in sorted(v.items()) if k not in TIMING_KEYS}
        if isinstance(v, list | tuple):
            return [plain(x) for x in v]
        if isinstance(v, np.generic):
            return plain(v.item())
        return v

    text = json.dumps(plain(value), sort_keys=True)
    return hashlib.sha256(text.encode()).hexdigest()[:16]


#: CMA-ES is pinned by its curve, within a relative tolerance, not by a hash. pycma's
#: eigendecompositions go through OpenBLAS, whose kernel (picked per CPU when numpy loads,
#: and different between OpenBLAS builds) changes the last bits: measured on one Intel
#: Xeon, the Prescott, Sandybridge, Haswell and SkylakeX kernels give curves that differ
#: by at most 5.6e-13 relative, so their exact hashes differ (two CI machines and one AMD
#: EPYC gave four hashes). A change of behaviour moves the curve by far more than this.
CMAES_CURVE_FILE = Path(__file__).with_name("behaviour_curves.json")
CMAES_RTOL = 1e-9


def _bbfo_row(method: str) -> dict[str, Any]:
    from voot.bench.sweep.bbfo import RunSpec, run_spec

    row: dict[str, Any] = run_spec(RunSpec("shekel", 3, method, (), 200, 0))
    return row


def _bbfo_digest(method: str) -> str:
    row = _bbfo_row(method)
    return _digest({k: row[k] for k in ("best_so_far", "status")})


def cmaes_curve() -> list[float]:
    """CMA-ES's best-so-far curve on the 3-D Shekel function (200 evaluations, seed 0)."""
    row = _bbfo_row("cmaes")
    if row["status"] != "ok":
        raise RuntimeError(f"the CMA-ES run failed: {row.get('error')}")
    return [float(v) for v in row["best_so_far"]]


def cmaes_curve_changes(pinned: list[float], got: list[float]) -> list[int]:
    """Indices where ``got`` differs from ``pinned`` by more than :data:`CMAES_RTOL`."""
    if len(pinned) != len(got):
        return list(range(max(len(pinned), len(got))))
    a, b = np.asarray(pinned), np.asarray(got)
    return np.flatnonzero(~np.isclose(b, a, rtol=CMAES_RTOL, atol=0.0)).tolist()


def _bbfo() -> dict[str, str]:
    return {f"bbfo/{m}": _bbfo_digest(m) for m in ("voo", "doo")}


def _plan_rows() -> dict[str, str]:
    from voot.bench.sweep.plan import PlanSpec, run_plan_spec

    specs = {
        "plan/shekel_chain/voot": PlanSpec("shekel_chain", 10, (), "voot", (), 300, 0),
        "plan/shekel_chain/pw_uct": PlanSpec("shekel_chain", 10, (), "pw_uct", (), 300, 0),
        "plan/shekel_chain/hoot": PlanSpec("shekel_chain", 10, (), "hoot", (), 300, 0),
        "plan/shekel_chain/doot": PlanSpec("shekel_chain", 3, (), "doot", (), 300, 0),
        "plan/kitchen_v1/hoot": PlanSpec("voot/KitchenClearing-v1", None, (), "hoot", (), 200, 0),
        "plan/kitchen_v1/rand_doot": PlanSpec(
            "voot/KitchenClearing-v1", None, (), "rand_doot", (), 200, 0
        ),
        "plan/kitchen_v0/voot": PlanSpec("voot/KitchenClearing-v0", None, (), "voot", (), 60, 0),
        "plan/kitchen_v1/voot": PlanSpec("voot/KitchenClearing-v1", None, (), "voot", (), 300, 0),
        "plan/kitchen_v1/pw_uct": PlanSpec(
            "voot/KitchenClearing-v1", None, (), "pw_uct", (), 300, 0
        ),
    }
    out = {}
    for name, spec in specs.items():
        row = run_plan_spec(spec)
        keep = ("best_so_far", "objects_left", "n_steps", "n_feasibility_checks", "n_nodes")
        out[name] = _digest({k: row.get(k) for k in keep} | {"status": row["status"]})
    return out


#: The v1 domains and the planners pinned on them: every tree planner and every sampling
#: (MPC) planner. The RL planners (``ppo``, ``ddpg``) need torch, which the core and dev
#: installs do not have, so they are pinned apart (:data:`V1_RL_PLANNERS`).
V1_PROBLEMS: dict[str, str] = {
    "kitchen_v1": "voot/KitchenClearing-v1",
    "conveyor_v1": "voot/ConveyorPacking-v1",
}
V1_PLANNERS: tuple[str, ...] = tuple(p for p in PLAN_PLANNERS if p not in RL_PLANNERS)
#: Simulations of each v1 run: 60 keeps all 22 runs at a few seconds in total.
V1_SIMULATIONS = 60
V1_FILE = Path(__file__).with_name("v1_fingerprints.json")
#: What a v1 fingerprint hashes: the best-so-far and objects-left curves, the simulator
#: calls per simulation, the best plan (its actions and rewards) and the search's counts.
#: On the conveyor every planner's best return stays at the infeasible first action's
#: -2.0 for 60 simulations, so there the calls curve and the counts carry the signal.
V1_KEYS: tuple[str, ...] = (
    "best_so_far",
    "objects_left",
    "calls_curve",
    "best_actions",
    "best_rewards",
    "n_steps",
    "n_feasibility_checks",
    "n_nodes",
    "status",
)


def v1_fingerprints() -> dict[str, str]:
    """``{"v1/<problem>/<planner>": hash}``: every planner of :data:`V1_PLANNERS` on both
    v1 domains, :data:`V1_SIMULATIONS` simulations, seed 0, default parameters.

    Exact hashes: the v1 runs do not go through BLAS in a way that moves bits (their
    hashes were checked equal under the Prescott, Haswell and SkylakeX OpenBLAS kernels,
    ``OPENBLAS_CORETYPE``, which move CMA-ES's).
    """
    from voot.bench.sweep.plan import PlanSpec, run_plan_spec

    out = {}
    for label, env_id in V1_PROBLEMS.items():
        for planner in V1_PLANNERS:
            row = run_plan_spec(PlanSpec(env_id, None, (), planner, (), V1_SIMULATIONS, 0))
            out[f"v1/{label}/{planner}"] = _digest({k: row.get(k) for k in V1_KEYS})
    return out


#: The RL planners, pinned apart (``tools/v1_rl_fingerprints.json``) because they need
#: torch and stable-baselines3 (the ``rl`` extra), which the core and dev installs lack.
V1_RL_PLANNERS: tuple[str, ...] = RL_PLANNERS
V1_RL_FILE = Path(__file__).with_name("v1_rl_fingerprints.json")
#: Simulations of each RL run, by planner and problem: small budgets that train.
#: The budget is matched to a VOOT search of that many simulations (its steps plus
#: pre-checks, as ``voot-bench plan --planners ppo ddpg`` runs them, default options).
#: DDPG updates after every step from step 100 (``learning_starts``): the other planners'
#: 60 simulations give 375 steps on the kitchen and 589 on the conveyor, so 275 and 489
#: gradient steps.
#: PPO updates only after a whole 2,048-step rollout: 300 simulations give 2,234 steps
#: on the kitchen and 220 give 2,311 on the conveyor (the first multiples of 20 with
#: over 150 steps of the updated policy; 280 and 200 leave it 29 and 47).
V1_RL_SIMULATIONS: dict[str, dict[str, int]] = {
    "ppo": {"kitchen_v1": 300, "conveyor_v1": 220},
    "ddpg": {"kitchen_v1": 60, "conveyor_v1": 60},
}
#: What an RL fingerprint holds exactly (hashed): the calls curve, the budget, the
#: episodes finished, the objects-left curve, the status and the steps at which the best
#: return improved. The episode count carries the training's signal where the curve does
#: not: an episode ends at an infeasible step, so it counts the policy's infeasible
#: actions (kitchen PPO at 300 simulations: 1,663 episodes in 2,234 steps).
#: On the conveyor every action of these budgets is infeasible (one step per episode),
#: so there the pin holds the budget and the task, not the learning.
V1_RL_EXACT_KEYS: tuple[str, ...] = (
    "calls_curve",
    "rl_steps",
    "n_episodes",
    "objects_left",
    "status",
)
#: The returns (``best_so_far`` and the values of ``best_by_step``) are compared within
#: this relative tolerance, not by their bits: they pass through float32 networks whose
#: last bits depend on torch's CPU kernel and thread count. Measured on one Intel Xeon
#: (AVX-512): the avx2 and avx512 kernels give the same bits, the scalar kernel
#: (``ATEN_CPU_CAPABILITY=default``) moves kitchen returns by up to 5.5e-6 relative
#: (DDPG's best; PPO's by 4.0e-7), two torch threads instead of one move DDPG's by
#: 5.9e-7 (PPO's not at all); episodes and improvement steps stay the same. A change of behaviour moves a
#: count or a step (measured: PPO's learning rate 1e-3 instead of 3e-4 gives 1,658 kitchen
#: episodes instead of 1,663; DDPG's 2e-3 instead of 1e-3 gives 215 instead of 213 and
#: another best). On the conveyor neither change is seen (every action is infeasible).
V1_RL_RTOL = 1e-4


def _v1_rl_fingerprint(row: dict[str, Any]) -> dict[str, Any]:
    """An RL row's fingerprint: ``exact`` (a hash), ``rl_steps`` (the budget, also in the
    hash, shown so that a test can see the run trained) and its returns, compared within
    :data:`V1_RL_RTOL` (:func:`v1_rl_changes`)."""
    improvements = row.get("best_by_step") or []
    exact = {k: row.get(k) for k in V1_RL_EXACT_KEYS} | {
        "improvement_steps": [int(s) for s, _ in improvements]
    }
    return {
        "exact": _digest(exact),
        "rl_steps": int(row.get("rl_steps") or 0),
        "best_so_far": [float(v) for v in row.get("best_so_far") or []],
        "best_by_step": [float(b) for _, b in improvements],
    }


def rl_installed() -> bool:
    """Whether the ``rl`` extra (torch and stable-baselines3) is importable."""
    import importlib.util

    return all(importlib.util.find_spec(m) is not None for m in ("torch", "stable_baselines3"))


def v1_rl_fingerprints() -> dict[str, dict[str, Any]]:
    """``{"v1/<problem>/<planner>": fingerprint}`` of the RL planners
    (:data:`V1_RL_PLANNERS`) on both v1 domains, :data:`V1_RL_SIMULATIONS`, seed 0,
    default options (:func:`_v1_rl_fingerprint`).

    The same seed gives bit-identical rows in one process and across processes (torch on
    one CPU thread, ``voot.rl.train``); another torch CPU kernel may move the returns'
    last bits, hence :data:`V1_RL_RTOL`.

    Raises:
        voot.rl.MissingExtraError: torch or stable-baselines3 is not installed.
        RuntimeError: a run failed.
    """
    from voot.bench.sweep.plan import PlanSpec, run_plan_spec
    from voot.rl import require_sb3

    require_sb3()
    out = {}
    for label, env_id in V1_PROBLEMS.items():
        for planner in V1_RL_PLANNERS:
            sims = V1_RL_SIMULATIONS[planner][label]
            row = run_plan_spec(PlanSpec(env_id, None, (), planner, (), sims, 0))
            if row["status"] != "ok":
                raise RuntimeError(f"the {planner} run on {label} failed: {row.get('error')}")
            out[f"v1/{label}/{planner}"] = _v1_rl_fingerprint(row)
    return out


def v1_rl_changes(pinned: dict[str, Any], got: dict[str, Any]) -> dict[str, list[str]]:
    """``{run: [what changed]}`` between two sets of RL fingerprints: a missing or extra
    run, another ``exact`` hash, or a return curve of another length or off by more than
    :data:`V1_RL_RTOL` relative (empty: none changed)."""
    out: dict[str, list[str]] = {}
    for key in sorted(pinned.keys() | got.keys()):
        a, b = pinned.get(key), got.get(key)
        if a is None or b is None:
            out[key] = ["missing" if b is None else "not pinned"]
            continue
        what = ["exact"] if a["exact"] != b["exact"] else []
        for curve in ("best_so_far", "best_by_step"):
            x, y = np.asarray(a[curve], dtype=float), np.asarray(b[curve], dtype=float)
            if x.shape != y.shape or not np.isclose(y, x, rtol=V1_RL_RTOL, atol=0.0).all():
                what.append(curve)
        if what:
            out[key] = what
    return out


def _compare_rl() -> bool:
    """Print the RL fingerprints' comparison line; whether they are unchanged."""
    pinned = json.loads(V1_RL_FILE.read_text())
    changes = v1_rl_changes(pinned, v1_rl_fingerprints())
    for key, what in changes.items():
        print(f"CHANGED {key}: {', '.join(what)}")
    n = len(pinned)
    print(f"{n - len(changes)} of {n} v1 RL fingerprints unchanged (returns within {V1_RL_RTOL})")
    return not changes


def _record_rl() -> None:
    got = v1_rl_fingerprints()
    V1_RL_FILE.write_text(json.dumps(got, indent=1, sort_keys=True) + "\n")
    print(f"{len(got)} v1 RL fingerprints -> {V1_RL_FILE}")


def _root_parallel() -> dict[str, str]:
    from voot.tree import make_chain, plan_root_parallel

    res = plan_root_parallel(
        make_chain("shekel", 10), "voot", 200, seed=0, n_trees=2, executor="serial"
    )
    return {"root_parallel/shekel10": _digest([res.best_return_curve, list(res.actions)])}


def _demo() -> dict[str, str]:
    from voot.bench.demos import kitchen_demo
    from voot.record.reader import read_recording

    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        for env_id in ("voot/KitchenClearing-v0", "voot/KitchenClearing-v1"):
            folder = Path(tmp) / env_id.replace("/", "_")
            summary = kitchen_demo.run(folder, 60, 0, video=False, verbose=False, env_id=env_id)
            data = summary.to_dict()
            for key in ("search_seconds", "total_seconds", "recording", "video"):
                data.pop(key, None)
            out[f"demo/{env_id}/json"] = _digest(data)
            rec = read_recording(summary.recording)
            out[f"demo/{env_id}/entities"] = _digest(sorted(rec.entities))
    return out


def _sweeps() -> dict[str, str]:
    """Whole sweeps through the store (bbfo and plan), rows hashed without timings."""
    from voot.bench.store.result_store import ResultStore
    from voot.bench.sweep.bbfo import build_specs
    from voot.bench.sweep.engine import run_sweep
    from voot.bench.sweep.plan import build_plan_specs

    out = {}
    with tempfile.TemporaryDirectory() as tmp:
        cases = {
            "sweep/bbfo": build_specs(["shekel"], [3], ["voo", "doo"], range(2), budget=80),
            "sweep/plan": build_plan_specs(
                ["shekel_chain", "kitchen_v1"], [3], ["voot", "pw_uct"], range(2), simulations=40
            ),
        }
        for name, specs in cases.items():
            store = ResultStore(Path(tmp) / name.replace("/", "_"), create=True)
            run_sweep(specs, store, progress=False)
            rows = sorted(store.load(), key=lambda r: r["run_id"])
            keep = ("run_id", "status", "best_so_far", "objects_left", "n_steps", "simulator_calls")
            out[name] = _digest([{k: r.get(k) for k in keep} for r in rows])
    return out


PARTS: dict[str, Callable[[], dict[str, str]]] = {
    "sweeps": _sweeps,
    "bbfo": _bbfo,
    "plan": _plan_rows,
    "root_parallel": _root_parallel,
    "demo": _demo,
}


def collect() -> dict[str, str]:
    out: dict[str, str] = {}
    for part in PARTS.values():
        out.update(part())
    return out


def main(argv: list[str]) -> int:
    if len(argv) == 2 and argv[0] == "bbfo-digest":
        print(_bbfo_digest(argv[1]))
        return 0
    if argv in (["record-rl"], ["compare-rl"]):
        if not rl_installed():
            print('the RL fingerprints need the rl extra: pip install -e ".[rl]"')
            return 2
        if argv[0] == "record-rl":
            _record_rl()
            return 0
        return 0 if _compare_rl() else 1
    if len(argv) != 2 or argv[0] not in ("record", "compare"):
        print(__doc__)
        return 2
    path = Path(argv[1])
    hashes = collect()
    curve = cmaes_curve()
    v1 = v1_fingerprints()
    if argv[0] == "record":
        path.write_text(json.dumps(hashes, indent=1, sort_keys=True) + "\n")
        CMAES_CURVE_FILE.write_text(json.dumps({"bbfo/cmaes": curve}, indent=1) + "\n")
        V1_FILE.write_text(json.dumps(v1, indent=1, sort_keys=True) + "\n")
        print(
            f"{len(hashes)} hashes -> {path}, CMA-ES's curve -> {CMAES_CURVE_FILE}, "
            f"{len(v1)} v1 fingerprints -> {V1_FILE}"
        )
        if rl_installed():
            _record_rl()
        return 0
    pinned_v1 = json.loads(V1_FILE.read_text())
    bad_v1 = sorted(k for k in pinned_v1.keys() | v1.keys() if pinned_v1.get(k) != v1.get(k))
    for k in bad_v1:
        print(f"CHANGED {k}: {pinned_v1.get(k)} -> {v1.get(k)}")
    print(f"{len(pinned_v1) - len(bad_v1)} of {len(pinned_v1)} v1 planner fingerprints unchanged")
    rl_ok = _compare_rl() if rl_installed() else True
    if not rl_installed():
        print("v1 RL fingerprints not checked: the rl extra (torch) is not installed")
    expected = json.loads(path.read_text())
    bad = sorted(k for k in expected.keys() | hashes.keys() if expected.get(k) != hashes.get(k))
    for k in bad:
        print(f"CHANGED {k}: {expected.get(k)} -> {hashes.get(k)}")
    moved = cmaes_curve_changes(json.loads(CMAES_CURVE_FILE.read_text())["bbfo/cmaes"], curve)
    if moved:
        print(f"CHANGED bbfo/cmaes: the curve moves by more than {CMAES_RTOL} at {moved[:5]}")
    total = len(expected) + 1
    print(f"{total - len(bad) - bool(moved)} of {total} outputs unchanged")
    return 1 if bad or moved or bad_v1 or not rl_ok else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
