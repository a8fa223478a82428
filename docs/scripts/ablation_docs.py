"""Redraw the ablation's table from the committed store into the docs.

Runs ``voot-bench ablation --out docs/data/ablation-v1 --table`` (settings selected on the
tuning seeds 1000-1004) for the problems whose runs are complete (:data:`PROBLEMS`) and
writes the table between the ``<!-- ablation-v1:table -->`` markers of
``docs/results-planning.md``, so the page shows what the store holds:

    python docs/scripts/ablation_docs.py
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from voot.bench.cli.main import main as bench
from voot.bench.report import docs_pages

STORE = "docs/data/ablation-v1"
PAGE = Path("docs/results-planning.md")
TUNING = "1000:1005"
#: The problems whose ablation runs are all in the store.
PROBLEMS = ("kitchen_v1", "conveyor_v1")


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


def main() -> None:
    docs_pages.rewrite_page(PAGE, {f"ablation-v1:{n}": body for n, body in render().items()})
    print(f"{PAGE}: ablation table redrawn from {STORE}")


if __name__ == "__main__":
    main()
