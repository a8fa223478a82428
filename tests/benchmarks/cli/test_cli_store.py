"""Tests of ``voot-bench compact`` and ``voot-bench measure store-speed`` (``shipped``:
tests/benchmarks/store/test_shipped.py)."""

from __future__ import annotations

from pathlib import Path

import pytest


def test_plan_compact_and_compact_commands(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from voot.bench.cli.main import main
    from voot.bench.store.compact import CompactConfig
    from voot.bench.store.result_store import ResultStore

    base = ["plan", "--problems", "shekel_chain", "--dims", "3", "--planners", "voot"]
    base += ["--seeds", "2", "--simulations", "30", "--grid", "default", "--workers", "1"]
    base += ["--no-progress", "--backend", "serial"]
    assert main([*base, "--out", str(tmp_path / "c"), "--compact", "--compact-points", "9"]) == 0
    store = ResultStore(tmp_path / "c")
    assert store.compact == CompactConfig(points=9)
    assert all("compact" in r for r in store.load(expand=False))
    # resumed without the flag: nothing runs, the store stays compact
    capsys.readouterr()
    assert main([*base, "--out", str(tmp_path / "c")]) == 0
    assert "2 already in the store" in capsys.readouterr().err and len(store) == 2
    assert main([*base, "--out", str(tmp_path / "c"), "--compact"]) == 2  # other settings
    assert "voot-bench compact" in capsys.readouterr().err
    assert main([*base, "--out", str(tmp_path / "f")]) == 0
    assert main(["compact", str(tmp_path / "f"), str(tmp_path / "f2"), "--points", "5"]) == 0
    out = capsys.readouterr().out
    assert "2 rows in" in out and "2 copied now" in out and "x smaller" in out
    # merged into a store with other runs: DST's rows counted, no size ratio (not like
    # with like)
    other_seeds = [a if a != "2" else "2:4" for a in base]
    assert main([*other_seeds, "--out", str(tmp_path / "g")]) == 0
    capsys.readouterr()
    assert main(["compact", str(tmp_path / "g"), str(tmp_path / "f2"), "--points", "5"]) == 0
    out = capsys.readouterr().out
    assert "2 copied now" in out and "f2: 4 rows" in out and "smaller" not in out
    assert ResultStore(tmp_path / "f2").compact == CompactConfig(points=5)
    with pytest.raises(SystemExit):  # argparse lists the valid spacings
        main(["compact", str(tmp_path / "f"), str(tmp_path / "f3"), "--spacing", "cubic"])
    assert "choose from 'log', 'linear'" in capsys.readouterr().err
    assert main(["compact", str(tmp_path / "f"), str(tmp_path / "f3"), "--points", "1"]) == 2
    assert "points must be" in capsys.readouterr().err


def test_store_speed_prints_both_layouts(
    capsys: pytest.CaptureFixture[str], monkeypatch: pytest.MonkeyPatch
) -> None:
    from voot.bench.cli.main import main
    from voot.bench.store import index as store_index

    monkeypatch.setattr(store_index, "RACY_NS", 0)
    assert main(["measure", "store-speed", "--rows", "2", "--length", "300", "--repeats", "1"]) == 0
    out = capsys.readouterr().out
    assert "| full |" in out and "| compact |" in out
    assert main(["measure", "store-speed", "--rows", "0"]) == 2
