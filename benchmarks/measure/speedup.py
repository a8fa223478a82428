"""``voot-bench measure speedup``: the tree search on the robot domains, old code against new.

The command materialises the code of a baseline commit (``git archive`` from the current
checkout, into a temporary folder), lays both it and the current checkout out as
importable ``voot`` packages the way pyproject's ``package-dir`` mapping installs them
(``envs`` as ``voot.envs``, ``models`` as ``voot.models``, ``benchmarks`` as
``voot.bench``), and runs the same workload for each in a fresh subprocess, one after
the other, with that folder first on ``PYTHONPATH``. It prints the CPU seconds of the
search (``time.process_time`` around :func:`voot.tree.plan`; the env's construction is
not counted), simulations per second, the ratio, and whether the two best-return curves
are bit-identical (their float64 bytes compared through a SHA-256).

For both it also splits the time of a simulation into the checks' MuJoCo
collision queries, arm IK and base planning (the ``last_timing`` each env step records,
wall-clock) and the rest: the env's own Python and the tree search with its adapter.

It needs a git checkout (a pip-installed wheel has no history to take the baseline
from). Workloads (:data:`WORKLOADS`) are the issue's: ``kitchen-voot``
(KitchenClearing-v0, VOOT, 2,000 simulations) and ``conveyor-pwuct``
(ConveyorPacking-v0, PW-UCT, 3,000 simulations), seed 0, each with the domain options of
:func:`voot.bench.protocol.problems.domain_options`.
"""

from __future__ import annotations

import hashlib
import io
import json
import os
import shutil
import subprocess
import sys
import tarfile
import tempfile
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

#: The commit the issue measures against (main before the speed work).
DEFAULT_BASELINE = "6af33b5"
#: Top-level folders of the repository and where pyproject installs them inside ``voot``.
PACKAGE_DIRS = {"envs": "envs", "models": "models", "benchmarks": "bench"}
#: Marker of the runner's result line on stdout.
RESULT_MARKER = "VOOT-SPEEDUP-RESULT "


class SpeedupError(RuntimeError):
    """The comparison cannot run (no git, no checkout, unknown commit, a failed run)."""


@dataclass(frozen=True)
class Workload:
    """One tree search: env id, planner, number of simulations and seed."""

    name: str
    env_id: str
    planner: str
    simulations: int
    seed: int = 0


#: The v1 domains' workloads (current code only: v1 did not exist at the baseline).
V1_WORKLOADS: dict[str, Workload] = {
    w.name: w
    for w in (
        Workload("kitchen-v1-voot", "voot/KitchenClearing-v1", "voot", 2000),
        Workload("conveyor-v1-pwuct", "voot/ConveyorPacking-v1", "pw_uct", 3000),
    )
}

#: The issue's workloads, by name.
WORKLOADS: dict[str, Workload] = {
    w.name: w
    for w in (
        Workload("kitchen-voot", "voot/KitchenClearing-v0", "voot", 2000),
        Workload("conveyor-pwuct", "voot/ConveyorPacking-v0", "pw_uct", 3000),
    )
}

# The program each subprocess runs: one search, its result as JSON on one marked line.
RUNNER = r"""
import hashlib, json, sys, time
spec = json.loads(sys.argv[1])
import gymnasium as gym
import voot
try:
    from voot.bench.protocol.problems import domain_options
    from voot.envs.core.problem import EnvProblem
except ModuleNotFoundError:  # a commit from before the rooms by concept (flat folders)
    from voot.bench.problems import domain_options
    from voot.envs.planning import EnvProblem
from voot.tree import plan

env = gym.make(spec["env_id"], disable_env_checker=True)
problem = EnvProblem(env.unwrapped, seed=spec["seed"])
u = problem.unwrapped
split = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0]
if spec["split"]:
    name = "transition" if hasattr(type(u), "transition") else "step"
    inner = getattr(u, name)

    def timed(action, inner=inner):
        out = inner(action)
        t = u.last_timing
        split[0] += t.ik
        split[1] += t.collision
        split[2] += t.planning
        split[3] += t.total
        return out

    setattr(u, name, timed)

    def stopwatch(check, slot):  # check, its seconds added to split[slot]

        def timed_check(action):
            t0 = time.perf_counter()
            out = check(action)
            split[slot] += time.perf_counter() - t0
            return out

        return timed_check

    if callable(getattr(u, "precheck", None)):  # v1: the kinematic pre-check, timed apart
        u.precheck = stopwatch(u.precheck, 4)
    for name in ("certainly_infeasible", "certainly_infeasible_values"):
        # v0: the env's exact pre-screen (either entry), timed apart; defined by the env's
        # class or a layer of it (the kitchen's: voot.envs.kitchen.screen), not the base's
        owner = next((k for k in type(u).__mro__ if name in vars(k)), None)
        if owner is not None and owner.__name__ != "ManipulationEnv":
            setattr(u, name, stopwatch(getattr(u, name), 5))
options = domain_options(spec["env_id"], None, spec["planner"])
wall, cpu = time.perf_counter(), time.process_time()
res = plan(problem, spec["planner"], spec["simulations"], seed=spec["seed"], **options)
cpu, wall = time.process_time() - cpu, time.perf_counter() - wall
curve = res.best_return_curve
out = {
    "voot": voot.__file__,
    "cpu": cpu,
    "wall": wall,
    "n_steps": int(res.n_steps),
    "n_feasibility_checks": int(res.n_feasibility_checks),
    "best_return": float(res.best_return),
    "curve_sha256": hashlib.sha256(curve.astype("<f8").tobytes()).hexdigest(),
    "curve": [float(v).hex() for v in curve] if spec["curve"] else None,
    "split": {
        "ik": split[0],
        "collision": split[1],
        "planning": split[2],
        "steps": split[3],
        "precheck": split[4],
        "prescreen": split[5],
    }
    if spec["split"]
    else None,
}
print("VOOT-SPEEDUP-RESULT " + json.dumps(out), flush=True)
"""


@dataclass(frozen=True)
class RunResult:
    """What one subprocess measured (see :data:`RUNNER`)."""

    workload: Workload
    code: str
    cpu: float
    wall: float
    n_steps: int
    n_feasibility_checks: int
    best_return: float
    curve_sha256: str
    curve: tuple[str, ...] | None = None
    split: Mapping[str, float] | None = None

    @property
    def sims_per_second(self) -> float:
        return self.workload.simulations / self.cpu if self.cpu > 0 else float("inf")


# ----- the code to compare -----------------------------------------------------------------
def repo_root(start: Path | None = None) -> Path:
    """The git checkout this module belongs to (or that holds ``start``).

    Raises:
        SpeedupError: If it is not a checkout of voot with its git history (e.g. a
            pip-installed wheel) or git is missing.
    """
    here = (start or Path(__file__)).resolve()
    root = here if here.is_dir() else here.parent
    for candidate in (root, *root.parents):
        if all((candidate / d).is_dir() for d in ("voot", *PACKAGE_DIRS)):
            root = candidate
            break
    else:
        raise SpeedupError(
            f"{here} is not inside a checkout of voot (voot/, envs/, models/, benchmarks/):"
            " voot-bench measure speedup must run from a git checkout (a pip-installed wheel has no"
            " git history to take the baseline from)"
        )
    if shutil.which("git") is None:
        raise SpeedupError(
            "git is not installed; voot-bench measure speedup needs it for the baseline"
        )
    probe = _git(root, "rev-parse", "--show-toplevel", check=False)
    if probe.returncode != 0:
        raise SpeedupError(
            f"{root} is not a git checkout: voot-bench measure speedup must run from a git checkout"
            " (a pip-installed wheel has no git history to take the baseline from)"
        )
    return root


def _git(root: Path, *args: str, check: bool = True) -> subprocess.CompletedProcess[bytes]:
    proc = subprocess.run(["git", "-C", str(root), *args], capture_output=True, check=False)
    if check and proc.returncode != 0:
        msg = proc.stderr.decode(errors="replace").strip()
        raise SpeedupError(f"git {' '.join(args)} failed: {msg}")
    return proc


def resolve_commit(root: Path, commit: str) -> str:
    """The full hash of ``commit`` in the checkout at ``root``."""
    proc = _git(root, "rev-parse", "--verify", "--quiet", f"{commit}^{{commit}}", check=False)
    if proc.returncode != 0:
        raise SpeedupError(
            f"commit {commit!r} is not in the repository at {root} (a shallow clone may lack"
            " it: fetch more history, or pass --baseline with a commit that is there)"
        )
    return proc.stdout.decode().strip()


def describe_checkout(root: Path) -> str:
    """``<short hash>`` of HEAD, with ``+ uncommitted changes`` if the tree is dirty."""
    head = _git(root, "rev-parse", "--short", "HEAD").stdout.decode().strip()
    dirty = _git(root, "status", "--porcelain", "--untracked-files=no").stdout.strip()
    return head + (" + uncommitted changes" if dirty else "")


def extract_commit(root: Path, commit: str, dest: Path) -> Path:
    """The tree of ``commit`` (its package folders) extracted into ``dest``."""
    folders = ["voot", *PACKAGE_DIRS]
    proc = _git(root, "archive", "--format=tar", commit, *folders)
    dest.mkdir(parents=True, exist_ok=True)
    with tarfile.open(fileobj=io.BytesIO(proc.stdout)) as tar:
        tar.extractall(dest, filter="data")
    return dest


def import_root(tree: Path, dest: Path) -> Path:
    """A folder holding ``voot`` laid out as pyproject installs it, for ``tree``'s code.

    ``dest/voot`` links every entry of ``tree/voot`` and adds ``envs``, ``models`` and
    ``bench`` for the repository's top-level folders (symbolic links; copies where links
    are not possible). Put ``dest`` first on ``PYTHONPATH`` to import that code.
    """
    pkg = dest / "voot"
    pkg.mkdir(parents=True, exist_ok=False)
    links = {entry.name: entry for entry in (tree / "voot").iterdir()}
    links.update({target: tree / src for src, target in PACKAGE_DIRS.items()})
    for name, src in links.items():
        if name == "__pycache__":
            continue
        link = pkg / name
        try:
            link.symlink_to(src.resolve(), target_is_directory=src.is_dir())
        except OSError:  # pragma: no cover - file systems without links
            if src.is_dir():
                shutil.copytree(src, link)
            else:
                shutil.copy2(src, link)
    return dest


# ----- running -------------------------------------------------------------------------------
def run_workload(
    root: Path,
    workload: Workload,
    code: str,
    *,
    split: bool = False,
    curve: bool = False,
    timeout: float | None = None,
) -> RunResult:
    """Run ``workload`` in a subprocess importing voot from ``root`` (see :func:`import_root`)."""
    spec = {
        "env_id": workload.env_id,
        "planner": workload.planner,
        "simulations": workload.simulations,
        "seed": workload.seed,
        "split": split,
        "curve": curve,
    }
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join([str(root), *filter(None, [env.get("PYTHONPATH")])])
    # one thread each, so that both runs get the same machine
    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        env[var] = "1"
    try:
        proc = subprocess.run(
            [sys.executable, "-c", RUNNER, json.dumps(spec)],
            cwd=root,
            env=env,
            capture_output=True,
            text=True,
            timeout=timeout,
            check=False,
        )
    except subprocess.TimeoutExpired:
        raise SpeedupError(f"{workload.name} ({code}) ran longer than {timeout} s") from None
    lines = [ln for ln in proc.stdout.splitlines() if ln.startswith(RESULT_MARKER)]
    if proc.returncode != 0 or not lines:
        tail = "\n".join(proc.stderr.strip().splitlines()[-15:])
        raise SpeedupError(
            f"{workload.name} ({code}) failed with exit status {proc.returncode}:\n{tail}"
        )
    out = json.loads(lines[-1][len(RESULT_MARKER) :])
    if not Path(out["voot"]).is_relative_to(root):
        raise SpeedupError(
            f"{workload.name} ({code}) imported voot from {out['voot']}, not from {root}"
        )
    return RunResult(
        workload=workload,
        code=code,
        cpu=float(out["cpu"]),
        wall=float(out["wall"]),
        n_steps=int(out["n_steps"]),
        n_feasibility_checks=int(out["n_feasibility_checks"]),
        best_return=float(out["best_return"]),
        curve_sha256=str(out["curve_sha256"]),
        curve=tuple(out["curve"]) if out["curve"] is not None else None,
        split=out["split"],
    )


@dataclass(frozen=True)
class Comparison:
    """The baseline's and the current code's runs of one workload.

    With repeats, ``baseline`` and ``current`` are each code's fastest run (least CPU
    time: on a shared machine the noise only ever adds time) and ``baseline_cpu`` and
    ``current_cpu`` hold every run's CPU seconds, in the order they ran (alternating).
    """

    baseline: RunResult
    current: RunResult
    baseline_cpu: tuple[float, ...] = ()
    current_cpu: tuple[float, ...] = ()
    #: Did every repeat of a code give the same curve as its first run?
    repeats_agree: bool = True

    @property
    def ratio(self) -> float:
        """Baseline CPU seconds over current CPU seconds."""
        return self.baseline.cpu / self.current.cpu if self.current.cpu > 0 else float("inf")

    @property
    def identical(self) -> bool:
        """Are the best-return curves bit-identical (same length and bytes), in every run?"""
        return self.repeats_agree and self.baseline.curve_sha256 == self.current.curve_sha256

    @property
    def repeats(self) -> int:
        """Runs of each code."""
        return max(len(self.current_cpu), 1)


def select_workloads(
    names: Sequence[str] | None, simulations: Sequence[str] | None = None
) -> list[Workload]:
    """The named workloads (all by default), with ``N`` or ``NAME=N`` simulation overrides."""
    chosen = list(names) if names else list(WORKLOADS)
    unknown = [n for n in chosen if n not in WORKLOADS]
    if unknown:
        raise SpeedupError(
            f"unknown workload(s) {', '.join(unknown)}; valid: {', '.join(WORKLOADS)}"
        )
    overrides: dict[str | None, int] = {}
    for item in simulations or ():
        key, _, value = item.rpartition("=")
        try:
            n = int(value)
        except ValueError:
            raise SpeedupError(f"--simulations: {item!r} is not N or NAME=N") from None
        if n < 1:
            raise SpeedupError(f"--simulations must be >= 1, got {n}")
        if key and key not in WORKLOADS:
            raise SpeedupError(f"--simulations: unknown workload {key!r}")
        overrides[key or None] = n
    out = []
    for name in chosen:
        w = WORKLOADS[name]
        n = overrides.get(name, overrides.get(None, w.simulations))
        out.append(replace(w, simulations=n))
    return out


def compare(
    workloads: Sequence[Workload],
    baseline: str = DEFAULT_BASELINE,
    *,
    repo: Path | None = None,
    split: bool = True,
    curve: bool = False,
    timeout: float | None = None,
    log: Any = None,
    repeats: int = 1,
) -> tuple[str, str, list[Comparison]]:
    """Run every workload with the baseline commit's code, then with the current code.

    With ``repeats`` > 1 the two alternate (baseline, current, baseline, ...) that many
    times each, and each code's fastest run is compared: the usual defence of a ratio
    against a shared machine's load, which comes and goes and only ever adds time.

    Returns:
        The baseline's full hash, a description of the current checkout, and one
        :class:`Comparison` per workload.
    """
    if not (isinstance(repeats, int) and repeats >= 1):
        raise SpeedupError(f"repeats must be an integer >= 1, got {repeats!r}")
    root = repo_root(repo)
    full = resolve_commit(root, baseline)
    current = describe_checkout(root)
    results = []
    with tempfile.TemporaryDirectory(prefix="voot-speedup-") as tmp:
        base_tree = extract_commit(root, full, Path(tmp) / "baseline-tree")
        base_root = import_root(base_tree, Path(tmp) / "baseline")
        cur_root = import_root(root, Path(tmp) / "current")
        for w in workloads:
            olds: list[RunResult] = []
            news: list[RunResult] = []
            for k in range(repeats):
                tag = f" (run {k + 1} of {repeats})" if repeats > 1 else ""
                if log is not None:
                    print(
                        f"{w.name}: {w.simulations} simulations, baseline {full[:7]}{tag} ...",
                        file=log,
                    )
                # both runs are timed alike (the split's bookkeeping costs both the same)
                old = run_workload(
                    base_root, w, "baseline", split=split, curve=curve, timeout=timeout
                )
                if log is not None:
                    print(f"{w.name}: {old.cpu:.1f} s; current code ...", file=log)
                new = run_workload(
                    cur_root, w, "current", split=split, curve=curve, timeout=timeout
                )
                if log is not None:
                    print(f"{w.name}: {new.cpu:.1f} s", file=log)
                olds.append(old)
                news.append(new)
            agree = all(r.curve_sha256 == olds[0].curve_sha256 for r in olds) and all(
                r.curve_sha256 == news[0].curve_sha256 for r in news
            )
            results.append(
                Comparison(
                    min(olds, key=lambda r: r.cpu),
                    min(news, key=lambda r: r.cpu),
                    tuple(r.cpu for r in olds),
                    tuple(r.cpu for r in news),
                    agree,
                )
            )
    return full, current, results


# ----- report --------------------------------------------------------------------------------
def split_line(run: RunResult) -> str:
    """Where a simulation's time goes (wall-clock, ms per simulation), for ``run``."""
    if run.split is None:
        return ""
    sims = run.workload.simulations
    parts = {
        "MuJoCo collision": run.split["collision"],
        "IK": run.split["ik"],
        "base planner": run.split["planning"],
    }
    env_python = max(run.split["steps"] - sum(parts.values()), 0.0)
    parts["other env Python"] = env_python
    precheck = float(run.split.get("precheck", 0.0))
    if precheck > 0:
        parts["kinematic pre-checks"] = precheck
    prescreen = float(run.split.get("prescreen", 0.0))
    if prescreen > 0:
        parts["v0 pre-screens"] = prescreen
    parts["tree search + adapter"] = max(run.wall - run.split["steps"] - precheck - prescreen, 0.0)
    total = run.wall
    cells = ", ".join(
        f"{name} {1e3 * sec / sims:.2f} ({100 * sec / total:.0f}%)" for name, sec in parts.items()
    )
    return f"  {1e3 * total / sims:.2f} ms wall per simulation = {cells}"


def format_report(baseline: str, current: str, comparisons: Sequence[Comparison]) -> str:
    """The table ``voot-bench measure speedup`` prints."""
    lines = [
        f"baseline: {baseline[:10]}   current: {current}",
        "CPU seconds of the search (process time), same machine, one after the other"
        + (
            f"; {comparisons[0].repeats} alternating runs each, the fastest shown"
            if comparisons and comparisons[0].repeats > 1
            else ""
        ),
        "",
        f"{'workload':<16} {'sims':>6} {'code':<9} {'cpu s':>8} {'sims/s':>8} {'ms/sim':>8}"
        f" {'steps':>7} {'checks':>9}  curve sha256",
    ]
    for c in comparisons:
        for run in (c.baseline, c.current):
            w = run.workload
            lines.append(
                f"{w.name:<16} {w.simulations:>6} {run.code:<9} {run.cpu:>8.2f}"
                f" {run.sims_per_second:>8.1f} {1e3 * run.cpu / w.simulations:>8.2f}"
                f" {run.n_steps:>7} {run.n_feasibility_checks:>9}  {run.curve_sha256[:16]}"
            )
        lines.append(
            f"{'':<16} {'':>6} {'ratio':<9} {c.ratio:>7.2f}x   best-return curve bit-identical:"
            f" {'yes' if c.identical else 'NO'}"
        )
        if c.repeats > 1:
            for code, cpus in (("baseline", c.baseline_cpu), ("current", c.current_cpu)):
                lines.append(f"  {code:<9}every run: " + ", ".join(f"{v:.2f}" for v in cpus))
        for run in (c.baseline, c.current):
            detail = split_line(run)
            if detail:
                lines.append(f"  {run.code:<9}" + detail.strip())
        lines.append("")
    return "\n".join(lines).rstrip() + "\n"


def report_json(baseline: str, current: str, comparisons: Sequence[Comparison]) -> dict[str, Any]:
    """The same as :func:`format_report`, as a JSON-ready dict."""

    def run_dict(r: RunResult) -> dict[str, Any]:
        return {
            "cpu": r.cpu,
            "wall": r.wall,
            "sims_per_second": r.sims_per_second,
            "n_steps": r.n_steps,
            "n_feasibility_checks": r.n_feasibility_checks,
            "best_return": r.best_return,
            "curve_sha256": r.curve_sha256,
            "split": dict(r.split) if r.split is not None else None,
        }

    return {
        "baseline": baseline,
        "current": current,
        "workloads": [
            {
                "name": c.current.workload.name,
                "env_id": c.current.workload.env_id,
                "planner": c.current.workload.planner,
                "simulations": c.current.workload.simulations,
                "seed": c.current.workload.seed,
                "baseline": run_dict(c.baseline),
                "current": run_dict(c.current),
                "ratio": c.ratio,
                "curve_identical": c.identical,
                "baseline_cpu_runs": list(c.baseline_cpu),
                "current_cpu_runs": list(c.current_cpu),
            }
            for c in comparisons
        ],
    }


def curve_digest(values: Sequence[float]) -> str:
    """SHA-256 of a curve's float64 bytes, as the runner computes it."""
    import numpy as np

    return hashlib.sha256(np.asarray(values, dtype="<f8").tobytes()).hexdigest()


def v1_cost(
    simulations: int | None = None,
    *,
    repo: Path | None = None,
    timeout: float | None = None,
    log: Any = None,
) -> list[RunResult]:
    """The v1 domains' cost per simulation with the current code (:data:`V1_WORKLOADS`)."""
    root = repo_root(repo)
    out = []
    with tempfile.TemporaryDirectory(prefix="voot-speedup-") as tmp:
        cur_root = import_root(root, Path(tmp) / "current")
        for w in V1_WORKLOADS.values():
            if simulations is not None:
                w = replace(w, simulations=simulations)
            if log is not None:
                print(f"{w.name}: {w.simulations} simulations, current code ...", file=log)
            out.append(run_workload(cur_root, w, "current", split=True, timeout=timeout))
    return out


def format_v1(runs: Sequence[RunResult]) -> str:
    """The table of :func:`v1_cost`."""
    lines = [
        "v1 domains, current code: CPU seconds of the search and where a simulation's time goes",
        "",
        f"{'workload':<18} {'sims':>6} {'cpu s':>8} {'ms/sim':>8} {'steps':>7} {'pre-checks':>10}",
    ]
    for run in runs:
        w = run.workload
        lines.append(
            f"{w.name:<18} {w.simulations:>6} {run.cpu:>8.2f} {1e3 * run.cpu / w.simulations:>8.2f}"
            f" {run.n_steps:>7} {run.n_feasibility_checks:>10}"
        )
        lines.append("  " + split_line(run).strip())
    return "\n".join(lines) + "\n"
