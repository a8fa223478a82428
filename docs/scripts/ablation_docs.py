"""Redraw the ablation's table from the committed store into the docs (issue 23).

Runs ``voot-bench ablation --out docs/data/ablation-v1 --table`` (settings selected on the
tuning seeds 1000-1004) for the problems whose runs are complete (:data:`PROBLEMS`) and
writes the table between the ``<!-- ablation-v1:table -->`` markers of
``docs/results-planning.md``, so the page shows what the store holds:

    python docs/scripts/ablation_docs.py
"""

from __future__ import annotations

import contextlib
import io
import re
import tempfile
from pathlib import Path

from voot.bench.cli.main import main as bench

STORE = "docs/data/ablation-v1"
PAGE = Path("docs/results-planning.md")
TUNING = "1000:1005"
#: The problems whose ablation runs are all in the store.
PROBLEMS = ("kitchen_v1", "conveyor_v1")


def _block(name: str) -> re.Pattern[str]:
    return re.compile(rf"(<!-- ablation-v1:{name} -->\n)(.*?)(<!-- /ablation-v1:{name} -->)", re.S)


def marked(text: str, name: str) -> str:
    """The block between the ``<!-- ablation-v1:NAME -->`` markers of ``text``."""
    m = _block(name).search(text)
    if m is None:
        raise SystemExit(f"{PAGE} has no <!-- ablation-v1:{name} --> markers")
    return m.group(2)


def replace(text: str, name: str, body: str) -> str:
    """``text`` with the ``NAME`` block's body replaced."""
    marked(text, name)
    return _block(name).sub(lambda m: m.group(1) + body + m.group(3), text)


def render(store: str | Path = STORE) -> dict[str, str]:
    """The page's ``table`` block, from ``store``."""
    with tempfile.TemporaryDirectory() as tmp:
        md = Path(tmp) / "ablation.md"
        argv = ["ablation", "--out", str(store), "--tuning-seeds", TUNING, "--table"]
        argv += ["--problems", *PROBLEMS, "--markdown", str(md)]
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            code = bench(argv)
        if code != 0:
            raise SystemExit(f"voot-bench {' '.join(argv)} failed ({code})")
        return {"table": md.read_text().strip() + "\n"}


def main() -> None:
    text = PAGE.read_text()
    for name, body in render().items():
        text = replace(text, name, body)
    PAGE.write_text(text)
    print(f"{PAGE}: ablation table redrawn from {STORE}")


if __name__ == "__main__":
    main()
