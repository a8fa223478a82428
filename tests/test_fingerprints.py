"""Pinned reference fingerprints: a change of behaviour that stays deterministic fails here.

The hashes are the committed ``tools/behaviour_hashes.json`` (recomputed by
``python tools/behaviour_hashes.py record``); this test recomputes the fast ones: black-box
runs of VOO, DOO and CMA-ES, and tree searches on the Shekel chain and on both kitchens.
"""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
SCRIPT = ROOT / "tools" / "behaviour_hashes.py"


@pytest.fixture(scope="module")
def hashes() -> object:
    spec = importlib.util.spec_from_file_location("behaviour_hashes", SCRIPT)
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_optimiser_and_tree_search_fingerprints(hashes: object) -> None:
    pinned = json.loads((ROOT / "tools" / "behaviour_hashes.json").read_text())
    got = {**hashes._bbfo(), **hashes._plan_rows()}  # type: ignore[attr-defined]
    assert got.keys() <= pinned.keys()
    changed = {k: (pinned[k], v) for k, v in got.items() if pinned[k] != v}
    assert not changed, f"behaviour changed (pinned, now): {changed}"
