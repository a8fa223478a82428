"""Tests of voot.bench.store.shipped and of the committed stores themselves (docs/data).

Every committed store reads back (checksums, row count and digest as in the manifest),
its figures and tables redraw with ``voot-bench plot``, and a sweep given the documented
command resumes from it without running anything.
"""

from __future__ import annotations

import json
import shutil
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any, NamedTuple

import pytest

from voot.bench.report import docs_pages
from voot.bench.store import shipped
from voot.bench.store.compact import CompactConfig
from voot.bench.store.format import Row, StoreError, make_row
from voot.bench.store.index import INDEX_NAME
from voot.bench.store.result_store import ResultStore

DATA = Path(__file__).resolve().parents[3] / shipped.DATA_DIR
STORES = [p.name for p in shipped.store_dirs(DATA)]


def docs_script(name: str) -> Any:
    """The module of ``docs/scripts/<name>.py`` (the scripts that write the docs' tables)."""
    import importlib.util

    path = DATA.parents[1] / "docs" / "scripts" / f"{name}.py"
    spec = importlib.util.spec_from_file_location(name, path)
    assert spec is not None and spec.loader is not None
    docs = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(docs)
    return docs


def test_the_manifest_lists_every_committed_store() -> None:
    assert STORES, f"no result stores under {DATA}"
    assert sorted(shipped.read_manifest(DATA)) == STORES


@pytest.mark.parametrize("name", STORES)
def test_a_committed_store_reads_back_and_redraws(name: str, tmp_path: Path) -> None:
    pytest.importorskip("matplotlib")
    before = sorted(p.name for p in (DATA / name).rglob("*") if p.name != INDEX_NAME)
    got = shipped.check_store(DATA, name)
    assert got["rows"] == len(ResultStore(DATA / name, create=False).row_files()) > 0
    from voot.bench.cli.main import main

    files = shipped.redraw(DATA / name, tmp_path, main)
    pngs = [f for f in files if f.suffix == ".png"]
    assert pngs and all(f.stat().st_size > 10_000 for f in pngs)
    tables = [f.read_text() for f in files if f.suffix == ".md"]
    assert tables and all("### Best return" in t or "|" in t for t in tables)
    after = sorted(p.name for p in (DATA / name).rglob("*") if p.name != INDEX_NAME)
    assert after == before  # reading works on a copy


class NeverRuns:
    name = "never"

    def map_unordered(self, fn: Callable[[Any], Row], items: Sequence[Any]) -> Iterator[Row]:
        assert not list(items), "a sweep of a committed store ran runs again"
        return iter(())


class DomainAblationExpected(NamedTuple):
    """What a complete domain ablation's store and table hold."""

    #: How the table names the domain.
    label: str
    #: How many of its evaluation runs are ``domain-planners-v1``'s, copied: VOOT and
    #: PW-UCT (UCB test) at v1's settings on seeds 0-19 where that store ran them at the
    #: ablation's simulations, none where it did not.
    shared_rows: int


#: The domain ablations of ``ablation_docs.DOMAINS`` complete in their stores.
DOMAIN_ABLATIONS = {
    "authors-domain": DomainAblationExpected(
        "base_model=footprint, big_box_ban=True, footprint_heuristic=geodesic, rooms=authors", 40
    ),
    "kitchen-footprint": DomainAblationExpected("base_model=footprint", 40),
    "conveyor-footprint": DomainAblationExpected("base_model=footprint", 0),
}


def documented_sweeps() -> dict[str, list[Any]]:
    """The specs of the commands docs/results-planning.md gives for each committed store."""
    from voot.bench.sweep.plan import build_plan_specs

    v1 = {"planners": ["voot", "pw_uct"], "seeds": range(5), "simulations": 2000}
    ablation_docs = docs_script("ablation_docs")
    return {
        "protocol-v1": protocol_v1_sweep(),
        "ablation-v1": ablation_sweep(),
        **{
            ablation_docs.DOMAINS[name].store.name: tuned_sweep(
                ablation_docs.DOMAINS[name].store.name, *ablation_docs.domain_specs(name)
            )
            for name in DOMAIN_ABLATIONS
        },
        "heldout-kitchen-v2": heldout_sweep("kitchen_v2", 2000),
        "heldout-conveyor-v2": heldout_sweep("conveyor_v2", 3000),
        "ladder-kitchen-v2": ladder_sweep("kitchen_v2", 2000),
        "ladder-conveyor-v2": ladder_sweep("conveyor_v2", 3000),
        "protocol-v1-same-seed": build_plan_specs(
            ["kitchen_v1", "conveyor_v1"], planners=PROTOCOL_V1_PLANNERS
        ),
        "plan-gym-control": build_plan_specs(
            ["Reacher-v5", "Swimmer-v5", "HalfCheetah-v5"],
            planners="voot pw_uct voronoi_pw cem mppi predictive_sampling random_shooting".split(),
            seeds=range(10),
            simulations=500,
            grid="default",
            horizon=20,
        ),
        "plan-v1-first-look": build_plan_specs(["kitchen_v1"], grid="default", **v1)  # type: ignore[arg-type]
        + build_plan_specs(
            ["kitchen_v1"],
            grid="default",
            env_kwargs={"pick_requires_free_carry": True},
            **v1,  # type: ignore[arg-type]
        ),
    }


#: The tree and MPC planners of the v1 protocol (each with the paper's grid).
PROTOCOL_V1_PLANNERS = (
    "voot doot rand_doot pw_uct voronoi_pw hoot cem mppi predictive_sampling".split()
)

#: The RL runs of the v1 protocol in the committed store: (problem, planner) -> seeds.
PROTOCOL_V1_RL = {
    ("voot/KitchenClearing-v1", "ppo"): range(20),
    ("voot/ConveyorPacking-v1", "ppo"): range(50),
    ("voot/KitchenClearing-v1", "ddpg"): range(20),
    ("voot/ConveyorPacking-v1", "ddpg"): range(50),
}


def protocol_v1_sweep() -> list[Any]:
    """The v1 protocol as docs/results-planning.md runs it: the grids on the tuning seeds
    1000-1004, the settings selected there on the paper's evaluation seeds (the tuned
    ``voot-bench plan --tuning-seeds``), and the RL runs (built directly: their specs need
    no stable-baselines3 to be named)."""
    from voot.bench.protocol.tuning import selected_specs, tuning_selections
    from voot.bench.sweep.plan import PlanSpec, build_plan_specs

    problems = ["kitchen_v1", "conveyor_v1"]
    tuning = build_plan_specs(problems, planners=PROTOCOL_V1_PLANNERS, seeds=range(1000, 1005))
    rows = ResultStore(DATA / "protocol-v1", create=False).load(kind="plan")
    evaluation = selected_specs(
        build_plan_specs(problems, planners=PROTOCOL_V1_PLANNERS), tuning_selections(tuning, rows)
    )
    budget = {"voot/KitchenClearing-v1": 2000, "voot/ConveyorPacking-v1": 3000}
    rl = [
        PlanSpec(problem, None, (), planner, (), budget[problem], seed)
        for (problem, planner), seeds in PROTOCOL_V1_RL.items()
        for seed in seeds
    ]
    return [*tuning, *evaluation, *rl]


def heldout_sweep(problem: str, simulations: int) -> list[Any]:
    """The held-out protocol as docs/results-planning.md runs it on a generated family at
    ``medium`` (``voot-bench plan --heldout``): every setting on the training layouts, the
    selected setting on the held-out layouts, one seed each."""
    from voot.bench.protocol.layouts import HELDOUT_LAYOUTS, TRAINING_LAYOUTS
    from voot.bench.protocol.tuning import selected_specs, tuning_selections
    from voot.bench.sweep.plan import build_plan_specs

    common: dict[str, Any] = {
        "planners": "voot pw_uct doot rand_doot uniform_t".split(),
        "seeds": [0],
        "simulations": simulations,
        "env_kwargs": {"difficulty": "medium"},
    }
    tuning = build_plan_specs([problem], layout_seeds=TRAINING_LAYOUTS, **common)
    name = "heldout-" + problem.replace("_", "-")
    rows = ResultStore(DATA / name, create=False).load(kind="plan")
    evaluation = selected_specs(
        build_plan_specs([problem], layout_seeds=HELDOUT_LAYOUTS, **common),
        tuning_selections(tuning, rows),
    )
    return [*tuning, *evaluation]


def ladder_sweep(problem: str, simulations: int) -> list[Any]:
    """The planner runs of docs/environments.md's difficulty ladder: VOOT and PW-UCT at
    their default settings on layouts 0-9 of every level."""
    from voot.bench.sweep.plan import build_plan_specs

    return [
        spec
        for level in ("easy", "medium", "hard")
        for spec in build_plan_specs(
            [problem],
            planners=["voot", "pw_uct"],
            seeds=[0],
            simulations=simulations,
            grid="default",
            env_kwargs={"difficulty": level},
            layout_seeds=range(10),
        )
    ]


def ablation_sweep() -> list[Any]:
    """The ablation as ``voot-bench ablation`` runs it: every variant's grid on the tuning
    seeds 1000-1004, its selected setting on seeds 0-19, on both v1 domains."""
    from voot.bench.protocol.ablation import ablation_specs, check_switches

    switches = check_switches(None)
    return tuned_sweep(
        "ablation-v1",
        ablation_specs(switches, range(1000, 1005)),
        ablation_specs(switches, range(20)),
    )


def tuned_sweep(store: str, tuning: list[Any], candidates: list[Any]) -> list[Any]:
    """The ``tuning`` runs and those of ``candidates`` at the setting the committed store's
    tuning runs select (the protocol of ``voot-bench ablation``)."""
    from voot.bench.protocol.tuning import selected_specs, tuning_selections

    rows = ResultStore(DATA / store, create=False).load(kind="plan")
    return [*tuning, *selected_specs(candidates, tuning_selections(tuning, rows))]


def assert_same_runs(rows: Sequence[Row], reference: dict[str, Row]) -> None:
    """Each of ``rows`` has the curves and counts of the row of its run id in ``reference``."""
    for r in rows:
        old = reference[r["run_id"]]
        for key in ("best_so_far", "objects_left", "n_steps", "n_feasibility_checks", "n_nodes"):
            assert r.get(key) == old.get(key), (r["run_id"], key)


def test_the_ablations_v1_rows_are_the_protocol_stores_rows() -> None:
    """v1 defaults unchanged: the ablation re-ran the protocol's VOOT and PW-UCT runs (same
    run ids) and got the same curves bit for bit."""
    protocol = {
        r["run_id"]: r for r in ResultStore(DATA / "protocol-v1", create=False).load(kind="plan")
    }
    rows = ResultStore(DATA / "ablation-v1", create=False).load(kind="plan", status="ok")
    shared = [r for r in rows if "variant" not in r["config"]]
    assert len(shared) == 200  # both domains' 120 tuning and 80 evaluation runs
    assert_same_runs(shared, protocol)


def test_the_ablation_table_in_the_docs_is_what_the_store_redraws() -> None:
    root = DATA.parents[1]
    docs = docs_script("ablation_docs")
    with shipped.store_copy(DATA / "ablation-v1") as copy:
        blocks = docs.render(copy)
    page = (root / "docs" / "results-planning.md").read_text()
    for name, body in blocks.items():
        assert docs.marked(page, name) == body, f"run python docs/scripts/ablation_docs.py ({name})"


def test_the_domain_planner_store_holds_only_its_documented_runs() -> None:
    """Every committed run of ``domain-planners-v1`` is one of the runs its script plans
    (``python docs/scripts/domain_planners.py run`` resumes the rest, running none of
    these again)."""
    docs = docs_script("domain_planners")
    planned = {spec.run_id for spec in docs.specs()}
    rows = ResultStore(DATA / "domain-planners-v1", create=False).load(kind="plan")
    assert rows and {row["run_id"] for row in rows} <= planned
    domains = len(docs.RUNS["conveyor_v1"][0]) + len(docs.RUNS["kitchen_v1"][0])
    assert len(docs.commands()) == domains * 3 + len(docs.LONG_RUNS)


def test_the_domain_planner_tables_in_the_docs_are_what_the_store_redraws() -> None:
    root = DATA.parents[1]
    docs = docs_script("domain_planners")
    with shipped.store_copy(DATA / "domain-planners-v1") as copy:
        blocks = docs.render(copy)
    page = (root / "docs" / "results-planning.md").read_text()
    for name, body in blocks.items():
        assert docs_pages.marked(page, name) == body, "run python docs/scripts/domain_planners.py"
    assert (
        "| authors_domain | VOOT (omega 0.3, reevaluations 2) | 20 of 20 |"
        in blocks["domain-planners-v1:conveyor"]
    )


@pytest.mark.parametrize("name", sorted(DOMAIN_ABLATIONS))
def test_a_domain_ablation_holds_only_its_runs_and_the_shared_rows_are_the_same(name: str) -> None:
    """The domain ablation's store holds only runs of its ablation (every setting on the
    tuning seeds 1000-1004 and on the evaluation seeds 0-19), and its runs that
    ``domain-planners-v1`` also holds (v1's settings on seeds 0-19, copied rather than
    re-run) have the same curves bit for bit."""
    docs = docs_script("ablation_docs")
    tuning, candidates = docs.domain_specs(name)
    rows = ResultStore(DATA / docs.DOMAINS[name].store.name, create=False).load(kind="plan")
    assert rows and {r["run_id"] for r in rows} <= {s.run_id for s in [*tuning, *candidates]}
    domain_planners = {
        r["run_id"]: r
        for r in ResultStore(DATA / "domain-planners-v1", create=False).load(kind="plan")
    }
    shared = [r for r in rows if r["run_id"] in domain_planners]
    assert len(shared) == DOMAIN_ABLATIONS[name].shared_rows
    assert_same_runs(shared, domain_planners)


@pytest.mark.parametrize("name", sorted(DOMAIN_ABLATIONS))
def test_a_domain_ablation_table_in_the_docs_is_what_the_store_redraws(name: str) -> None:
    docs = docs_script("ablation_docs")
    assert name in docs.TABLED
    store, problem = docs.DOMAINS[name].store.name, docs.DOMAINS[name].problem
    with shipped.store_copy(DATA / store) as copy:
        blocks = docs.render_domain(name, copy)
    page = (DATA.parents[1] / "docs" / "results-planning.md").read_text()
    for marker, body in blocks.items():
        assert docs_pages.marked(page, marker) == body, "run python docs/scripts/ablation_docs.py"
    # judged as the paper's problem, in the domain
    table = blocks[f"{store}:table"]
    assert f"| v1 | {problem} | voot |" in table and f"| pw_authors | {problem} |" in table
    assert f"Every run is in the domain {DOMAIN_ABLATIONS[name].label}." in table


@pytest.mark.parametrize("name", sorted(DOMAIN_ABLATIONS))
def test_copy_shared_rows_copies_the_ablations_runs_of_the_domain_planner_store_once(
    name: str, tmp_path: Path
) -> None:
    docs = docs_script("ablation_docs")
    store = tmp_path / "ablation"
    shared_rows = DOMAIN_ABLATIONS[name].shared_rows
    assert docs.copy_shared_rows(name, store, DATA / "domain-planners-v1") == shared_rows
    assert docs.copy_shared_rows(name, store, DATA / "domain-planners-v1") == 0
    copied = {p.stem for p in ResultStore(store, create=False).row_files()}
    assert copied <= {s.run_id for s in docs.domain_specs(name)[1]}


@pytest.mark.parametrize("name", sorted(documented_sweeps()))
def test_the_documented_sweep_resumes_from_the_committed_store_running_nothing(
    name: str, tmp_path: Path
) -> None:
    from voot.bench.sweep.engine import run_sweep

    specs = documented_sweeps()[name]
    copy = tmp_path / name
    shutil.copytree(DATA / name, copy, ignore=shutil.ignore_patterns(INDEX_NAME))
    summary = run_sweep(specs, ResultStore(copy), NeverRuns(), progress=False)
    assert summary.ran == 0 and summary.skipped == summary.total == len(specs)


def bbfo_row(seed: int) -> Row:
    config = {"function": "shekel", "dim": 3, "method": "voo", "params": {}, "budget": 4}
    best = [float(seed), float(seed), seed + 1.0, seed + 1.0]
    return make_row("bbfo", {**config, "seed": seed}, status="ok", wall_time=0.1, best_so_far=best)


def small_store(root: Path, compact: bool = False) -> Path:
    store = ResultStore(root / "s", compact=CompactConfig() if compact else None)
    for i in range(3):
        store.write(bbfo_row(i))
    return store.path


def test_manifest_catches_lost_added_and_changed_rows(tmp_path: Path) -> None:
    path = small_store(tmp_path, compact=True)
    shipped.write_manifest(tmp_path)
    entry = shipped.read_manifest(tmp_path)["s"]
    assert entry["rows"] == 3 and entry["compact"] is True
    assert shipped.check_store(tmp_path, "s")["sha256"] == entry["sha256"]
    row_file = sorted((path / "runs").iterdir())[0]
    data = row_file.read_bytes()
    row_file.unlink()
    with pytest.raises(StoreError, match="rows 2, the manifest says 3"):
        shipped.check_store(tmp_path, "s")
    row_file.write_bytes(data)
    extra = ResultStore(path).write(bbfo_row(9))
    with pytest.raises(StoreError, match="rows 4"):
        shipped.check_store(tmp_path, "s")
    extra.unlink()
    assert shipped.check_store(tmp_path, "s")["rows"] == 3
    manifest = json.loads((tmp_path / shipped.MANIFEST_NAME).read_text())
    manifest["s"]["sha256"] = "0" * 64
    (tmp_path / shipped.MANIFEST_NAME).write_text(json.dumps(manifest))
    with pytest.raises(StoreError, match="sha256"):
        shipped.check_store(tmp_path, "s")
    with pytest.raises(StoreError, match="not in"):
        shipped.check_store(tmp_path, "other")
    (tmp_path / shipped.MANIFEST_NAME).write_text("[")
    with pytest.raises(StoreError, match="voot-bench shipped --write"):
        shipped.read_manifest(tmp_path)


def test_a_corrupt_committed_row_is_a_store_error(tmp_path: Path) -> None:
    path = small_store(tmp_path)
    shipped.write_manifest(tmp_path)
    row_file = sorted((path / "runs").iterdir())[0]
    data = row_file.read_bytes()
    assert b'"wall_time":0.1' in data
    row_file.write_bytes(data.replace(b'"wall_time":0.1', b'"wall_time":0.2'))
    with pytest.raises(StoreError, match="changed since it was written"):
        shipped.check_store(tmp_path, "s")


@pytest.mark.parametrize("name", STORES)
def test_every_committed_store_names_an_edited_or_truncated_row(name: str, tmp_path: Path) -> None:
    """Every committed store carries row checksums (the two written before them were
    given theirs, issue 26): a value edited in the middle of a row, or a row cut short
    (a crash mid-copy), is a StoreError naming the row's file on load, never read as
    it is."""
    copy = tmp_path / name
    shutil.copytree(DATA / name, copy, ignore=shutil.ignore_patterns(INDEX_NAME))
    assert ResultStore(copy, create=False).checksums_required
    rows = sorted((copy / "runs").iterdir())
    row_file = rows[len(rows) // 2]
    data = row_file.read_bytes()
    i = data.index(b'"wall_time":') + len(b'"wall_time":')
    digit = data[i : i + 1]
    assert digit.isdigit()
    row_file.write_bytes(data[:i] + (b"1" if digit != b"1" else b"2") + data[i + 1 :])
    with pytest.raises(StoreError, match=rf"{row_file}: result row changed since it was written"):
        ResultStore(copy, create=False).load()
    row_file.write_bytes(data[: len(data) // 2])
    with pytest.raises(StoreError, match=rf"{row_file}: corrupt result row \(.*line 1 column"):
        ResultStore(copy, create=False).load()


def test_old_stores_get_their_checksums_and_committed_ones_must_have_them(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A store written before row checksums read an edited row as it was; check_store now
    refuses such a store, and add_row_checksums (voot-bench shipped --add-checksums)
    gives its rows their checksum, the rows otherwise as they were."""
    from voot.bench.cli.main import main

    path = small_store(tmp_path)
    header = json.loads((path / "voot-results.json").read_text())
    del header["row_checksum"]
    (path / "voot-results.json").write_text(json.dumps(header, indent=1) + "\n")
    for f in (path / "runs").iterdir():  # rows as an old voot wrote them
        row = json.loads(f.read_bytes())
        del row["checksum"]
        f.write_bytes(json.dumps(row, separators=(",", ":")).encode())
    old = ResultStore(path, create=False)
    before = old.load()
    assert not old.checksums_required
    shipped.write_manifest(tmp_path)
    with pytest.raises(StoreError, match="a committed store without row checksums"):
        shipped.check_store(tmp_path, "s")
    first = sorted((path / "runs").iterdir())[0]
    edited = first.read_bytes().replace(b'"wall_time":0.1', b'"wall_time":0.2')
    saved = first.read_bytes()
    first.write_bytes(edited)
    assert ResultStore(path, create=False).load()[0]["wall_time"] == 0.2  # read as it is
    first.write_bytes(saved)
    assert main(["shipped", "--root", str(tmp_path), "--add-checksums"]) == 0
    assert "s: 3 rows given a checksum" in capsys.readouterr().out
    assert shipped.add_row_checksums(path) == 0  # done: nothing more to do
    new = ResultStore(path, create=False)
    assert new.checksums_required and new.load() == before and new.verify() == 3
    shipped.write_manifest(tmp_path)
    assert shipped.check_store(tmp_path, "s")["rows"] == 3
    first.write_bytes(first.read_bytes().replace(b'"wall_time":0.1', b'"wall_time":0.2'))
    with pytest.raises(StoreError, match=f"{first}: result row changed"):
        ResultStore(path, create=False).load()


def test_the_cli_checks_and_redraws(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    pytest.importorskip("matplotlib")
    from voot.bench.cli.main import main

    small_store(tmp_path / "data")
    assert main(["shipped", "--root", str(tmp_path / "data"), "--write"]) == 0
    assert main(["shipped", "--root", str(tmp_path / "data"), "--out", str(tmp_path / "o")]) == 0
    out = capsys.readouterr().out
    assert "s: 3 rows, checksums and manifest ok; redrawn: s-bbfo.png, s-bbfo.md" in out
    assert (tmp_path / "o" / "s" / "s-bbfo.png").stat().st_size > 1000
    assert main(["shipped", "--root", str(tmp_path / "none")]) == 2


def test_the_protocol_pages_tables_are_what_the_committed_store_redraws(tmp_path: Path) -> None:
    """docs/results-planning.md shows the v1 protocol's tables as the store redraws them."""
    pytest.importorskip("matplotlib")
    root = DATA.parents[1]
    docs = docs_script("protocol_v1_docs")
    with shipped.store_copy(DATA / "protocol-v1") as copy:
        blocks = docs.render(copy, tmp_path)
    page = (root / "docs" / "results-planning.md").read_text()
    for name, body in blocks.items():
        assert docs.marked(page, name) == body, (
            f"run python docs/scripts/protocol_v1_docs.py ({name})"
        )
    assert sorted(p.name for p in tmp_path.glob("*.png")) == [
        "plan-calls.png",
        "plan-cpu-seconds.png",
        "plan-simulations.png",
    ]


@pytest.mark.parametrize("name", ["heldout-kitchen-v2", "heldout-conveyor-v2"])
def test_the_heldout_tables_are_what_the_committed_store_redraws(name: str, tmp_path: Path) -> None:
    """docs/results-planning.md shows the held-out protocol's tables as the store redraws."""
    pytest.importorskip("matplotlib")
    root = DATA.parents[1]
    docs = docs_script("heldout_docs")
    assert name in docs.STORES
    with shipped.store_copy(DATA / name) as copy:
        body = docs.render(copy, tmp_path)
    page = (root / "docs" / "results-planning.md").read_text()
    assert docs.marked(page, name) == body, "run python docs/scripts/heldout_docs.py"
    assert body.count("| 20 layouts, 20 runs |") == 5  # each planner on the 20 held-out
    assert "Settings selected on training layouts 1000-1019" in body
