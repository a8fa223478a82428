"""Redraw the ablations' tables from the committed stores into the docs, and resume the
ablation in the authors' domain.

The planner ablation: ``voot-bench ablation --out docs/data/ablation-v1 --table``
(settings selected on the tuning seeds 1000-1004) for the problems whose runs are
complete (:data:`PROBLEMS`), written between the ``<!-- ablation-v1:table -->`` markers
of ``docs/results-planning.md``, so the page shows what the store holds:

    python docs/scripts/ablation_docs.py

The same tuning in the authors' domain (issue 35: the faithful conveyor,
``voot/ConveyorPacking-v3``'s settings as keywords of ``conveyor_v1``), for VOOT and
PW-UCT with both widening tests (the switches :data:`AUTHORS_SWITCHES`), in
``docs/data/ablation-authors-domain-v1``; resumed (every run not in the store yet) by

    python docs/scripts/ablation_docs.py run-authors-domain

Its evaluation runs at v1's settings are runs ``docs/data/domain-planners-v1`` already
holds (the same run ids: the same problem, keywords, planner, setting, seed and
simulations); :func:`copy_shared_rows` copies those rows rather than running them again.
"""

from __future__ import annotations

import tempfile
from collections.abc import Sequence
from pathlib import Path
from typing import Any

from voot.bench.cli.main import main as bench
from voot.bench.report import docs_pages
from voot.envs.conveyor.config import CONVEYOR_PRESETS

STORE = "docs/data/ablation-v1"
PAGE = Path("docs/results-planning.md")
TUNING = "1000:1005"
#: The problems whose ablation runs are all in the store.
PROBLEMS = ("kitchen_v1", "conveyor_v1")

#: The ablation in the authors' domain: its store, the store whose rows it shares, its
#: switches (v1's defaults and PW-UCT's widening as the authors coded it) and domain (the
#: keywords that make ``voot/ConveyorPacking-v3`` of v1).
AUTHORS_STORE = Path("docs/data/ablation-authors-domain-v1")
SHARED_STORE = Path("docs/data/domain-planners-v1")
AUTHORS_SWITCHES = ("v1", "pw_authors")
AUTHORS_DOMAIN: dict[str, Any] = {
    k: v for k, v in CONVEYOR_PRESETS["v3"].items() if k not in CONVEYOR_PRESETS["v1"]
}


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


def authors_domain_command(store: str | Path = AUTHORS_STORE) -> list[str]:
    """The ``voot-bench`` command line of the ablation in the authors' domain."""
    kwargs = [
        f"{k}={str(v).lower() if isinstance(v, bool) else v}" for k, v in AUTHORS_DOMAIN.items()
    ]
    return [
        "ablation", "--out", str(store), "--compact", "--switches", *AUTHORS_SWITCHES,
        "--problems", "conveyor_v1", "--tuning-seeds", TUNING, "--seeds", "0:20",
        "--env-kwargs", *kwargs,
    ]  # fmt: skip


def authors_domain_specs() -> tuple[list[Any], list[Any]]:
    """The ablation's runs in the authors' domain: ``(tuning runs, evaluation candidates)``
    (every setting on seeds 0-19; the sweep runs the setting selected on the tuning runs)."""
    from voot.bench.protocol.ablation import ablation_specs, check_switches

    switches = check_switches(list(AUTHORS_SWITCHES))

    def specs(seeds: range) -> list[Any]:
        return ablation_specs(switches, seeds, problems=["conveyor_v1"], env_kwargs=AUTHORS_DOMAIN)

    return specs(range(1000, 1005)), specs(range(20))


def copy_shared_rows(store: str | Path = AUTHORS_STORE, shared: str | Path = SHARED_STORE) -> int:
    """Copy into ``store`` (a compact store, made if missing) the rows of ``shared`` that
    are evaluation runs of the ablation in the authors' domain; the number copied now."""
    from voot.bench.store.result_store import compact_store

    wanted = {spec.run_id for spec in authors_domain_specs()[1]}
    return compact_store(shared, store, run_ids=wanted)["copied"]


def main(argv: Sequence[str] = ()) -> None:
    if list(argv) == ["run-authors-domain"]:
        print(f"{AUTHORS_STORE}: {copy_shared_rows()} rows copied from {SHARED_STORE}")
        command = authors_domain_command()
        print("voot-bench " + " ".join(command), flush=True)
        raise SystemExit(bench(command))
    if argv:
        raise SystemExit(f"usage: {Path(__file__).name} [run-authors-domain]; got {' '.join(argv)}")
    docs_pages.rewrite_page(PAGE, {f"ablation-v1:{n}": body for n, body in render().items()})
    print(f"{PAGE}: ablation table redrawn from {STORE}")


if __name__ == "__main__":
    import sys

    main(sys.argv[1:])
