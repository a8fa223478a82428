"""The result stores that ship with the repository (under ``docs/data/``): manifest and redraw.

A clean checkout must redraw every figure and table of the docs from the committed stores
with ``voot-bench plot``, with no run, and a later session must be able to resume a sweep
from them. This module names what "the committed stores are intact" means:

* a **manifest** (``docs/data/stores.json``, :data:`MANIFEST_NAME`): per store, the number
  of row files and a SHA-256 over their names and row checksums (:func:`store_digest`),
  so a row lost or changed on the way (git, a copy) is caught, not only a corrupt one;
* :func:`check_store`: every row file verified (:meth:`ResultStore.verify`), the rows all
  readable through the store's reading path, their count and digest as in the manifest;
* :func:`redraw`: ``voot-bench plot`` of a store into a folder (figures and tables), on a
  copy of the store, so reading it leaves the committed directory as it was (the index a
  load writes is derived data and is not committed).

``voot-bench shipped`` checks and redraws them all; ``voot-bench shipped --write``
rewrites the manifest after a store was added or extended.
"""

from __future__ import annotations

import hashlib
import json
import shutil
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from voot.bench.store.format import (
    CHECKSUM_KEY,
    HEADER_NAME,
    ROW_CHECKSUM,
    StoreError,
    row_bytes,
    verify_row_bytes,
)
from voot.bench.store.index import INDEX_NAME, write_atomic
from voot.bench.store.result_store import ResultStore

#: The manifest's file name, in the folder that holds the stores.
MANIFEST_NAME = "stores.json"
#: Where the repository keeps its stores (relative to the repository's root).
DATA_DIR = "docs/data"


def store_dirs(root: str | Path) -> list[Path]:
    """The result stores directly under ``root`` (folders with a store header), by name."""
    base = Path(root)
    return sorted(p for p in base.iterdir() if (p / HEADER_NAME).is_file())


def store_digest(path: str | Path) -> dict[str, Any]:
    """``{"rows": n, "sha256": ..., "compact": bool}`` of the store at ``path``.

    The digest covers every row file's name and its row checksum, in name order; the
    checksums themselves cover the bytes (every file is verified while reading it).
    """
    store = ResultStore(path, create=False)
    h = hashlib.sha256()
    n = 0
    for row_path in store.row_files():
        data = row_path.read_bytes()
        store._read_row(row_path)  # parse, validate, verify the checksum
        tail = data.rsplit(f'"{CHECKSUM_KEY}":'.encode(), 1)[-1]
        h.update(row_path.name.encode() + b":" + tail.strip())
        n += 1
    return {"rows": n, "sha256": h.hexdigest(), "compact": store.compact is not None}


def manifest(root: str | Path) -> dict[str, dict[str, Any]]:
    """The manifest of every store under ``root`` (name -> :func:`store_digest`)."""
    return {p.name: store_digest(p) for p in store_dirs(root)}


def write_manifest(root: str | Path) -> Path:
    """Write ``root/stores.json`` from the stores there; returns its path."""
    path = Path(root) / MANIFEST_NAME
    path.write_text(json.dumps(manifest(root), indent=1, sort_keys=True) + "\n")
    return path


def read_manifest(root: str | Path) -> dict[str, dict[str, Any]]:
    """The committed manifest (StoreError naming the file if missing or not one)."""
    path = Path(root) / MANIFEST_NAME
    try:
        data = json.loads(path.read_bytes())
    except (OSError, ValueError) as exc:
        raise StoreError(
            f"{path}: no readable manifest of the committed stores ({exc}); write it with"
            " voot-bench shipped --write"
        ) from None
    if not isinstance(data, dict):
        raise StoreError(f"{path}: a manifest must be a JSON object of store names")
    return data


def check_store(root: str | Path, name: str) -> dict[str, Any]:
    """Verify the store ``root/name`` against the manifest; its digest.

    Raises:
        StoreError: a corrupt row, a store the manifest does not list, or a row count or
            digest that differs from the manifest's (rows lost, added or changed).
    """
    expected = read_manifest(root).get(name)
    path = Path(root) / name
    if expected is None:
        raise StoreError(f"{path}: not in {Path(root) / MANIFEST_NAME}; add it with --write")
    if not ResultStore(path, create=False).checksums_required:
        # rows without a checksum would be read as they are, edited or not: a committed
        # store carries them, so that a changed row is an error naming its file
        raise StoreError(
            f"{path}: a committed store without row checksums; give its rows one with"
            " voot-bench shipped --add-checksums, then rewrite the manifest (--write)"
        )
    with store_copy(path) as copy:
        got = store_digest(copy)
        rows = ResultStore(copy, create=False).load(status=None)
    if len(rows) != got["rows"]:  # pragma: no cover - load and the files disagree
        raise StoreError(f"{path}: {got['rows']} row files but {len(rows)} rows read")
    for key in ("rows", "sha256"):
        if got[key] != expected.get(key):
            raise StoreError(
                f"{path}: {key} {got[key]!r}, the manifest says {expected.get(key)!r} (rows"
                " lost, added or changed since the manifest was written)"
            )
    return got


def add_row_checksums(path: str | Path) -> int:
    """Give every row of the store at ``path`` its checksum; the number of rows rewritten.

    For a store written before row checksums (:mod:`voot.bench.store.result_store`, "Old stores"):
    each row file without a checksum is parsed and validated, then rewritten atomically
    as :func:`~voot.bench.store.format.row_bytes` writes rows now (compact JSON, the
    checksum last): the same row, checked by comparing both files' JSON. The header then
    gets ``"row_checksum"``, last, so that a store interrupted halfway is still an old
    store (rows with and without checksums load) and a rerun finishes it. From then on an
    edited row is a :class:`StoreError` naming its file on every load, where before it
    was read as it was.
    """
    store = ResultStore(path, create=False)
    n = 0
    for row_path in store.row_files():
        data = row_path.read_bytes()
        row = store._read_row(row_path)  # parsed and validated (a checksum, if any, verified)
        if verify_row_bytes(data, str(row_path), required=False):
            continue
        new = row_bytes(row)
        body = {k: v for k, v in json.loads(new).items() if k != CHECKSUM_KEY}
        if json.dumps(body, sort_keys=True) != json.dumps(json.loads(data), sort_keys=True):
            raise StoreError(f"{row_path}: the row does not survive a rewrite; left as it is")
        write_atomic(row_path, new)
        n += 1
    if not store.checksums_required:
        header = {**store.header, "row_checksum": ROW_CHECKSUM}
        write_atomic(store.header_path, (json.dumps(header, indent=1) + "\n").encode())
    return n


@contextmanager
def store_copy(path: str | Path) -> Iterator[Path]:
    """A temporary copy of the store at ``path`` without its index (removed afterwards)."""
    tmp = Path(tempfile.mkdtemp(prefix="voot-shipped-"))
    try:
        copy = tmp / Path(path).name
        shutil.copytree(path, copy, ignore=shutil.ignore_patterns(INDEX_NAME, ".*.tmp"))
        yield copy
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def redraw(
    path: str | Path, out_dir: str | Path, command: Callable[[list[str]], int]
) -> list[Path]:
    """``voot-bench plot`` of the store at ``path`` into ``out_dir``: the figures against
    simulations and (plan stores) seconds, and the tables as markdown. Returns the files.

    ``command`` runs one ``voot-bench`` command line (its words after ``voot-bench``) and
    returns its exit status, e.g. :func:`voot.bench.cli.main.main`: the store layer
    does not import the command line, which imports it.

    Raises:
        StoreError: the store cannot be read; RuntimeError: ``voot-bench plot`` failed.
    """
    import contextlib
    import io

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    name = Path(path).name
    with store_copy(path) as copy:
        kinds = {r["kind"] for r in ResultStore(copy, create=False).load()}
        files: list[Path] = []
        for kind in sorted(kinds):
            stem = out / f"{name}-{kind}"
            args = ["plot", str(copy), "--kind", kind, "--png", f"{stem}.png"]
            args += ["--markdown", f"{stem}.md"]
            if kind == "plan":
                args += ["--png-seconds", f"{stem}-seconds.png"]
            with (
                contextlib.redirect_stdout(io.StringIO()),
                contextlib.redirect_stderr(io.StringIO()) as err,
            ):
                try:
                    status = command(args)
                except Exception as exc:
                    raise RuntimeError(f"voot-bench {' '.join(args)} failed: {exc}") from exc
            if status != 0:
                raise RuntimeError(f"voot-bench {' '.join(args)} failed: {err.getvalue().strip()}")
            files += [Path(a) for a in args if a.startswith(str(stem))]
    return files
