"""Tiny ``voot-bench`` command lines shared by the tests of the command line (a helper,
not a test module): each runs in a second or two."""

from __future__ import annotations

#: ``voot-bench plan`` options: two planners, two seeds, 12 simulations on the 3-D chain.
PLAN_TINY = (
    "--problems shekel_chain --dims 3 --planners voot pw_uct --seeds 2 --simulations 12"
    " --grid default --workers 1 --no-progress"
).split()


def tree_snapshot(root: object) -> dict[str, bytes | None]:
    """Every path under ``root`` (a folder) with its bytes (None for a folder): what a
    refused command must leave as it was. A store's reader index (``.index-*``, rows'
    digest a reader rewrites, :mod:`voot.bench.store.index`) is left out: it is derived
    from the rows, which are compared."""
    from pathlib import Path

    base = Path(str(root))
    return {
        str(p.relative_to(base)): (None if p.is_dir() else p.read_bytes())
        for p in sorted(base.rglob("*"))
        if not p.name.startswith(".index-")
    }


def assert_refused(argv: list[str], root: object, capsys: object, *needles: str) -> str:
    """Run ``voot-bench argv``: it must exit 2 with one line ``voot-bench: error: ...``
    holding every one of ``needles`` (no traceback) and leave every file under ``root``
    (the test's folder: stores, outputs) as it was. Returns the error line."""
    from voot.bench.cli.main import main

    before = tree_snapshot(root)
    status = main(argv)
    err = capsys.readouterr().err  # type: ignore[attr-defined]
    lines = [line for line in err.splitlines() if line.strip()]
    assert status == 2, (status, err)
    assert "Traceback" not in err, err
    assert lines and lines[-1].startswith("voot-bench: error: "), err
    assert [line for line in lines if "error" in line] == [lines[-1]], err
    for needle in needles:
        assert needle in lines[-1], (needle, lines[-1])
    assert tree_snapshot(root) == before, "a refused command changed files"
    return lines[-1]
