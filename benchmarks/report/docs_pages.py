"""Generated sections of the docs pages: the blocks between ``<!-- NAME -->`` and
``<!-- /NAME -->`` markers, which the scripts under ``docs/scripts/`` rewrite from the
committed stores (and the tests compare with what the stores redraw to).
"""

from __future__ import annotations

import contextlib
import io
import re
from collections.abc import Callable, Mapping
from pathlib import Path


def block(marker: str) -> re.Pattern[str]:
    """The ``<!-- MARKER -->`` ... ``<!-- /MARKER -->`` block: groups (start, body, end)."""
    return re.compile(rf"(<!-- {marker} -->\n)(.*?)(<!-- /{marker} -->)", re.S)


def marked(text: str, marker: str) -> str:
    """The body of the ``MARKER`` block of ``text``; ValueError if it has none."""
    m = block(marker).search(text)
    if m is None:
        raise ValueError(f"no <!-- {marker} --> markers")
    return m.group(2)


def replace_block(text: str, marker: str, body: str) -> str:
    """``text`` with the ``MARKER`` block's body replaced by ``body``."""
    marked(text, marker)
    return block(marker).sub(lambda m: m.group(1) + body + m.group(3), text)


def rewrite_page(page: Path, blocks: Mapping[str, str]) -> None:
    """Rewrite the file ``page`` with the body of each ``MARKER`` block replaced by
    ``blocks[MARKER]`` (nothing is written if one of them has no markers)."""
    text = page.read_text()
    for marker, body in blocks.items():
        text = replace_block(text, marker, body)
    page.write_text(text)


def run_quietly(command: Callable[[list[str]], int], argv: list[str]) -> None:
    """Run the ``voot-bench`` command line ``argv`` with ``command`` (e.g.
    :func:`voot.bench.cli.main.main`), its output swallowed; RuntimeError with its error
    output if it fails."""
    with (
        contextlib.redirect_stdout(io.StringIO()),
        contextlib.redirect_stderr(io.StringIO()) as err,
    ):
        code = command(argv)
    if code != 0:
        raise RuntimeError(f"voot-bench {' '.join(argv)} failed ({code}): {err.getvalue().strip()}")
