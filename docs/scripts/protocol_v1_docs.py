"""Redraw the v1 protocol's figures and tables from the committed store into the docs.

Runs ``voot-bench plot`` and ``voot-bench claims`` on ``docs/data/protocol-v1`` (settings
selected on the tuning seeds 1000-1004) and writes the figures to
``docs/figures/protocol-v1/`` and the tables between the ``<!-- protocol-v1:... -->``
markers of ``docs/results-planning.md``, so the page always shows what the store holds:

    python docs/scripts/protocol_v1_docs.py
"""

from __future__ import annotations

import contextlib
import io
import re
import tempfile
from pathlib import Path

from voot.bench.cli.main import main as bench

STORE = "docs/data/protocol-v1"
FIGURES = Path("docs/figures/protocol-v1")
PAGE = Path("docs/results-planning.md")
TUNING = "1000:1005"


def _run(argv: list[str]) -> None:
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        code = bench(argv)
    if code != 0:
        raise SystemExit(f"voot-bench {' '.join(argv)} failed ({code})")


def _block(name: str) -> re.Pattern[str]:
    """The ``<!-- protocol-v1:NAME -->`` ... ``<!-- /protocol-v1:NAME -->`` block: (start, body, end)."""
    return re.compile(rf"(<!-- protocol-v1:{name} -->\n)(.*?)(<!-- /protocol-v1:{name} -->)", re.S)


def _replace(text: str, name: str, body: str) -> str:
    pattern = _block(name)
    if not pattern.search(text):
        raise SystemExit(f"{PAGE} has no <!-- protocol-v1:{name} --> markers")
    return pattern.sub(lambda m: m.group(1) + body + m.group(3), text)


def render(store: str | Path = STORE, figures: str | Path = FIGURES) -> dict[str, str]:
    """The figures (written to ``figures``) and the page's marked blocks, by marker name."""
    Path(figures).mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory() as tmp:
        tables, claims = Path(tmp) / "tables.md", Path(tmp) / "claims.md"
        plot = ["plot", str(store), "--tuning-seeds", TUNING, "--axes-dir", str(figures)]
        _run([*plot, "--markdown", str(tables)])
        _run(["claims", str(store), "--tuning-seeds", TUNING, "--markdown", str(claims)])
        # the page has its own headings and figure captions; keep the tables
        body = tables.read_text().split("### Figures")[0].replace("### ", "#### ")
        return {"tables": body.strip() + "\n", "claims": claims.read_text().strip() + "\n"}


def marked(text: str, name: str) -> str:
    """The block between the ``<!-- protocol-v1:NAME -->`` markers of ``text``."""
    match = _block(name).search(text)
    if match is None:
        raise SystemExit(f"no <!-- protocol-v1:{name} --> markers")
    return match.group(2)


def main() -> None:
    text = PAGE.read_text()
    for name, body in render().items():
        text = _replace(text, name, body)
    PAGE.write_text(text)
    print(f"figures in {FIGURES}, tables in {PAGE}")


if __name__ == "__main__":
    main()
