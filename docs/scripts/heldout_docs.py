"""Redraw the held-out protocol's figures and tables from the committed store (issue 24).

Runs ``voot-bench plot docs/data/heldout-kitchen-v2 --heldout`` (settings selected on the
training layouts 1000-1019, reported on the held-out layouts 0-19), writes the figures
into ``docs/figures/heldout-kitchen-v2/`` and the tables between the
``<!-- heldout-kitchen-v2:tables -->`` markers of ``docs/results-planning.md``:

    python docs/scripts/heldout_docs.py
"""

from __future__ import annotations

import contextlib
import io
import re
import tempfile
from pathlib import Path

from voot.bench.cli import main as bench

STORE = "docs/data/heldout-kitchen-v2"
PAGE = Path("docs/results-planning.md")
FIGURES = Path("docs/figures/heldout-kitchen-v2")
NAME = "heldout-kitchen-v2:tables"


def _block() -> re.Pattern[str]:
    return re.compile(rf"(<!-- {NAME} -->\n)(.*?)(<!-- /{NAME} -->)", re.S)


def marked(text: str) -> str:
    """The block between the page's ``<!-- heldout-kitchen-v2:tables -->`` markers."""
    m = _block().search(text)
    if m is None:
        raise SystemExit(f"{PAGE} has no <!-- {NAME} --> markers")
    return m.group(2)


def render(store: str | Path, figures: str | Path) -> str:
    """The tables (Markdown) of ``store``'s held-out runs; the figures go to ``figures``."""
    with tempfile.TemporaryDirectory() as tmp:
        md = Path(tmp) / "heldout.md"
        argv = ["plot", str(store), "--heldout", "--png", str(Path(figures) / "plan.png")]
        argv += ["--axes-dir", str(figures), "--markdown", str(md)]
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            code = bench(argv)
        if code != 0:
            raise SystemExit(f"voot-bench {' '.join(argv)} failed ({code})")
        return md.read_text().strip() + "\n"


def main() -> None:
    FIGURES.mkdir(parents=True, exist_ok=True)
    text = PAGE.read_text()
    marked(text)
    body = render(STORE, FIGURES)
    PAGE.write_text(_block().sub(lambda m: m.group(1) + body + m.group(3), text))
    print(f"{PAGE}: held-out tables redrawn from {STORE}; figures in {FIGURES}")


if __name__ == "__main__":
    main()
