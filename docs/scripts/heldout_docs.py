"""Redraw the held-out protocol's figures and tables from the committed stores.

For each store of :data:`STORES` (``docs/data/heldout-kitchen-v2`` ...), runs ``voot-bench
plot STORE --heldout`` (settings selected on the training layouts 1000-1019, reported on
the held-out layouts 0-19), writes the figures into ``docs/figures/<name>/`` and the
tables between the ``<!-- <name>:tables -->`` markers of ``docs/results-planning.md``:

    python docs/scripts/heldout_docs.py
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from voot.bench.cli.main import main as bench
from voot.bench.report import docs_pages

#: The committed held-out stores (under docs/data/) the page shows.
STORES = ("heldout-kitchen-v2", "heldout-conveyor-v2")
PAGE = Path("docs/results-planning.md")


def marked(text: str, name: str) -> str:
    """The block between the page's ``<!-- NAME:tables -->`` markers."""
    return docs_pages.marked(text, f"{name}:tables")


def render(store: str | Path, figures: str | Path) -> str:
    """The tables (Markdown) of ``store``'s held-out runs; the figures go to ``figures``."""
    with tempfile.TemporaryDirectory() as tmp:
        md = Path(tmp) / "heldout.md"
        argv = ["plot", str(store), "--heldout", "--png", str(Path(figures) / "plan.png")]
        argv += ["--axes-dir", str(figures), "--markdown", str(md)]
        docs_pages.run_quietly(bench, argv)
        return md.read_text().strip() + "\n"


def main() -> None:
    blocks = {}
    for name in STORES:
        figures = Path("docs/figures") / name
        figures.mkdir(parents=True, exist_ok=True)
        blocks[f"{name}:tables"] = render(Path("docs/data") / name, figures)
        print(f"{name}: tables redrawn into {PAGE}; figures in {figures}")
    docs_pages.rewrite_page(PAGE, blocks)


if __name__ == "__main__":
    main()
