"""Redraw the ablations' tables from the committed stores into the docs, and resume the
ablations on the domain switches.

The planner ablation: ``voot-bench ablation --out docs/data/ablation-v1 --table``
(settings selected on the tuning seeds 1000-1004) for the problems whose runs are
complete (:data:`PROBLEMS`), written between the ``<!-- ablation-v1:table -->`` markers
of ``docs/results-planning.md``, so the page shows what the store holds:

    python docs/scripts/ablation_docs.py

The same tuning on a domain switch of issue 35 (:data:`DOMAINS`), for VOOT and PW-UCT
with both widening tests (the switches :data:`SWITCHES_ON_DOMAINS`), each in its own
store; resumed (every run not in the store yet) by

    python docs/scripts/ablation_docs.py run-authors-domain     # the faithful conveyor
    python docs/scripts/ablation_docs.py run-kitchen-footprint  # the kitchen, exact footprint
    python docs/scripts/ablation_docs.py run-conveyor-footprint # the conveyor, exact footprint

A domain's table sits between its ``<!-- STORE:table -->`` markers once its tuning is
complete (:data:`TABLED`; the table counts the evaluation seeds each row holds), redrawn
with the other. Its evaluation
runs at v1's settings are runs ``docs/data/domain-planners-v1`` already holds (the same
run ids: the same problem, keywords, planner, setting, seed and simulations);
:func:`copy_shared_rows` copies those rows rather than running them again.
"""

from __future__ import annotations

import tempfile
from collections.abc import Sequence
from pathlib import Path
from typing import Any, NamedTuple

from voot.bench.cli.main import main as bench
from voot.bench.report import docs_pages
from voot.envs.conveyor.config import CONVEYOR_PRESETS

STORE = "docs/data/ablation-v1"
PAGE = Path("docs/results-planning.md")
#: The tuning seeds and the evaluation seeds of every ablation here.
TUNING_SEEDS, EVALUATION_SEEDS = range(1000, 1005), range(20)
TUNING = f"{TUNING_SEEDS.start}:{TUNING_SEEDS.stop}"
#: The problems whose ablation runs are all in the store.
PROBLEMS = ("kitchen_v1", "conveyor_v1")


class DomainAblation(NamedTuple):
    """The planner ablation on one domain switch: ``problem`` made with ``env_kwargs``,
    its runs in ``store``."""

    store: Path
    problem: str
    env_kwargs: dict[str, Any]

    @property
    def marker(self) -> str:
        """The name of its table's markers in the page."""
        return f"{self.store.name}:table"


#: The store whose rows the domain ablations share (their evaluation runs at v1's
#: settings), and their switches: v1's defaults and PW-UCT's widening as the authors
#: coded it.
SHARED_STORE = Path("docs/data/domain-planners-v1")
SWITCHES_ON_DOMAINS = ("v1", "pw_authors")
#: The authors' domain: the keywords that make ``voot/ConveyorPacking-v3`` of v1.
AUTHORS_DOMAIN: dict[str, Any] = {
    k: v for k, v in CONVEYOR_PRESETS["v3"].items() if k not in CONVEYOR_PRESETS["v1"]
}
DOMAINS: dict[str, DomainAblation] = {
    "authors-domain": DomainAblation(
        Path("docs/data/ablation-authors-domain-v1"), "conveyor_v1", AUTHORS_DOMAIN
    ),
    "kitchen-footprint": DomainAblation(
        Path("docs/data/ablation-kitchen-footprint-v1"), "kitchen_v1", {"base_model": "footprint"}
    ),
    "conveyor-footprint": DomainAblation(
        Path("docs/data/ablation-conveyor-footprint-v1"), "conveyor_v1", {"base_model": "footprint"}
    ),
}
#: The domains whose table is in the page.
TABLED: tuple[str, ...] = ("authors-domain", "kitchen-footprint", "conveyor-footprint")


def marked(text: str, name: str) -> str:
    """The block between the ``<!-- ablation-v1:NAME -->`` markers of ``text``."""
    return docs_pages.marked(text, f"ablation-v1:{name}")


def render(store: str | Path = STORE) -> dict[str, str]:
    """The page's ``table`` block, from ``store``."""
    with tempfile.TemporaryDirectory() as tmp:
        md = Path(tmp) / "ablation.md"
        argv = ["ablation", "--out", str(store), "--tuning-seeds", TUNING, "--table"]
        argv += ["--problems", *PROBLEMS, "--markdown", str(md)]
        docs_pages.run_quietly(bench, argv)
        return {"table": md.read_text().strip() + "\n"}


def render_domain(name: str, store: str | Path | None = None) -> dict[str, str]:
    """The page's block of domain ``name`` (the ablation's table of its runs, settings
    selected on the tuning seeds), from ``store`` (default: the domain's)."""
    domain = DOMAINS[name]
    with tempfile.TemporaryDirectory() as tmp:
        md = Path(tmp) / "ablation.md"
        argv = ["ablation", "--out", str(store or domain.store), "--tuning-seeds", TUNING]
        argv += ["--table", "--problems", domain.problem, "--env-kwargs", *_assignments(domain)]
        docs_pages.run_quietly(bench, [*argv, "--markdown", str(md)])
        table = md.read_text().strip()
    return {domain.marker: f"{table}\n\n{selected_line(store or domain.store)}\n"}


def selected_line(store: str | Path) -> str:
    """The setting each planner's tuning selected, as a sentence."""
    from voot.bench.report.plan_runs import plan_data
    from voot.bench.store.result_store import ResultStore

    rows = ResultStore(store, create=False).load(kind="plan")
    data = plan_data(rows, tuning_seeds=TUNING_SEEDS)
    return "Selected settings: " + "; ".join(f"{d.planner} {d.label}" for d in data) + "."


def _assignments(domain: DomainAblation) -> list[str]:
    """The domain's keywords as ``NAME=VALUE`` arguments of ``--env-kwargs``."""
    return [
        f"{k}={str(v).lower() if isinstance(v, bool) else v}" for k, v in domain.env_kwargs.items()
    ]


def domain_command(name: str, store: str | Path | None = None) -> list[str]:
    """The ``voot-bench`` command line of the ablation on domain ``name``."""
    domain = DOMAINS[name]
    return [
        "ablation", "--out", str(store or domain.store), "--compact",
        "--switches", *SWITCHES_ON_DOMAINS, "--problems", domain.problem,
        "--tuning-seeds", TUNING, "--seeds", f"{EVALUATION_SEEDS.start}:{EVALUATION_SEEDS.stop}",
        "--env-kwargs", *_assignments(domain),
    ]  # fmt: skip


def domain_specs(name: str) -> tuple[list[Any], list[Any]]:
    """The ablation's runs on domain ``name``: ``(tuning runs, evaluation candidates)``
    (every setting on seeds 0-19; the sweep runs the setting selected on the tuning runs)."""
    from voot.bench.protocol.ablation import ablation_specs, check_switches

    domain = DOMAINS[name]
    switches = check_switches(list(SWITCHES_ON_DOMAINS))

    def specs(seeds: range) -> list[Any]:
        return ablation_specs(
            switches, seeds, problems=[domain.problem], env_kwargs=domain.env_kwargs
        )

    return specs(TUNING_SEEDS), specs(EVALUATION_SEEDS)


def copy_shared_rows(
    name: str, store: str | Path | None = None, shared: str | Path = SHARED_STORE
) -> int:
    """Copy into ``store`` (default: the domain's; a compact store, made if missing) the
    rows of ``shared`` that are evaluation runs of the ablation on domain ``name``; the
    number copied now."""
    from voot.bench.store.result_store import compact_store

    wanted = {spec.run_id for spec in domain_specs(name)[1]}
    return compact_store(shared, store or DOMAINS[name].store, run_ids=wanted)["copied"]


def main(argv: Sequence[str] = ()) -> None:
    runs = {f"run-{name}": name for name in DOMAINS}
    if len(argv) == 1 and argv[0] in runs:
        name = runs[argv[0]]
        store = DOMAINS[name].store
        print(f"{store}: {copy_shared_rows(name)} rows copied from {SHARED_STORE}")
        command = domain_command(name)
        print("voot-bench " + " ".join(command), flush=True)
        raise SystemExit(bench(command))
    if argv:
        raise SystemExit(f"usage: {Path(__file__).name} [{' | '.join(runs)}]; got {' '.join(argv)}")
    blocks = {f"ablation-v1:{n}": body for n, body in render().items()}
    for name in TABLED:
        blocks.update(render_domain(name))
    docs_pages.rewrite_page(PAGE, blocks)
    print(f"{PAGE}: ablation tables redrawn from {STORE} and {', '.join(TABLED) or 'no domain'}")


if __name__ == "__main__":
    import sys

    main(sys.argv[1:])
