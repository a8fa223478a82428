"""Redraw the v1 protocol's figures and tables from the committed store into the docs.

Runs ``voot-bench plot`` and ``voot-bench claims`` on ``docs/data/protocol-v1`` (settings
selected on the tuning seeds 1000-1004) and writes the figures to
``docs/figures/protocol-v1/`` and the tables between the ``<!-- protocol-v1:... -->``
markers of ``docs/results-planning.md``, so the page always shows what the store holds:

    python docs/scripts/protocol_v1_docs.py
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from voot.bench.cli.main import main as bench
from voot.bench.report import docs_pages

STORE = "docs/data/protocol-v1"
FIGURES = Path("docs/figures/protocol-v1")
PAGE = Path("docs/results-planning.md")
TUNING = "1000:1005"


def render(store: str | Path = STORE, figures: str | Path = FIGURES) -> dict[str, str]:
    """The figures (written to ``figures``) and the page's marked blocks, by marker name."""
    Path(figures).mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        tables, claims = Path(tmp) / "tables.md", Path(tmp) / "claims.md"
        plot = ["plot", str(store), "--tuning-seeds", TUNING, "--axes-dir", str(figures)]
        docs_pages.run_quietly(bench, [*plot, "--markdown", str(tables)])
        docs_pages.run_quietly(
            bench, ["claims", str(store), "--tuning-seeds", TUNING, "--markdown", str(claims)]
        )
        # the page has its own headings and figure captions; keep the tables
        body = tables.read_text().split("### Figures")[0].replace("### ", "#### ")
        return {"tables": body.strip() + "\n", "claims": claims.read_text().strip() + "\n"}


def marked(text: str, name: str) -> str:
    """The block between the ``<!-- protocol-v1:NAME -->`` markers of ``text``."""
    return docs_pages.marked(text, f"protocol-v1:{name}")


def main() -> None:
    docs_pages.rewrite_page(PAGE, {f"protocol-v1:{n}": body for n, body in render().items()})
    print(f"figures in {FIGURES}, tables in {PAGE}")


if __name__ == "__main__":
    main()
