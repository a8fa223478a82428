"""Tests of ``voot-bench select``, ``plot`` and ``claims``: options of the other kind of
run are refused."""

from __future__ import annotations

from pathlib import Path

import pytest
from cli_fixtures import PLAN_TINY

from voot.bench.cli.main import main


def test_plot_options_of_the_other_kind(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "plan"
    argv = ["plan", "--out", str(out), *PLAN_TINY]
    argv[argv.index("--seeds") + 1] = "1"
    assert main(argv) == 0
    assert main(["plot", str(out), "--regret"]) == 2
    assert "apply to bbfo runs" in capsys.readouterr().err
    assert main(["plot", str(out), "--kind", "bbfo"]) == 2
    assert "no finished bbfo runs" in capsys.readouterr().err
    bbfo = tmp_path / "bbfo"
    small = ["--functions", "rastrigin", "--dims", "3", "--methods", "random", "--seeds", "1"]
    assert main(["bbfo", "--out", str(bbfo), *small, "--budget", "5", "--workers", "1"]) == 0
    assert main(["plot", str(bbfo), "--png-seconds", "x.png"]) == 2
    assert "apply to plan runs" in capsys.readouterr().err


def test_claims_and_plot_refuse_tuning_seeds_the_store_cannot_split(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """Tuning seeds absent from the store selected on nothing (yet the caption said they
    were tuned), and tuning seeds covering the whole store reported the selection's own
    seeds; both went through without a word. Also: a missing store and an empty one."""
    out = tmp_path / "plan"
    assert main(["plan", "--out", str(out), *PLAN_TINY]) == 0  # seeds 0 and 1
    capsys.readouterr()
    for command in (["claims"], ["plot"]):
        assert main([*command, str(out), "--tuning-seeds", "1000:1005"]) == 2
        assert "no runs of the tuning seeds 1000-1004 in the store (its seeds: 0-1)" in (
            capsys.readouterr().err
        )
        assert main([*command, str(out), "--tuning-seeds", "0:2"]) == 2
        assert "would be tuning on the test set" in capsys.readouterr().err
    assert main(["claims", str(out), "--tuning-seeds", "0:1"]) == 0
    assert "Settings selected on tuning seeds 0," in capsys.readouterr().out
    assert main(["claims", str(out), "--ablation", "--tuning-seeds", "7:9"]) == 2
    assert "no runs of the tuning seeds 7-8" in capsys.readouterr().err
    assert main(["claims", str(tmp_path / "nowhere")]) == 2
    assert "no voot result store here" in capsys.readouterr().err
    from voot.bench.store.result_store import ResultStore

    ResultStore(tmp_path / "empty")
    assert main(["claims", str(tmp_path / "empty")]) == 2
    assert "no finished plan runs in this store" in capsys.readouterr().err


def test_plot_and_claims_redraw_a_store_of_layouts(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    """A store whose rows have layout seeds (a held-out protocol's) redraws: one curve per
    family and planner, settings selected on the training layouts, intervals over layouts."""
    from plan_fixtures import LAYOUT_LABEL, layout_rows

    from voot.bench.store.result_store import ResultStore

    out = tmp_path / "heldout"
    store = ResultStore(out)
    for r in layout_rows():
        store.write(r)
    png, md = tmp_path / "fig.png", tmp_path / "tables.md"
    argv = ["plot", str(out), "--heldout", "--png", str(png), "--markdown", str(md)]
    assert main([*argv, "--axes-dir", str(tmp_path / "axes")]) == 0
    printed = capsys.readouterr().out
    assert png.read_bytes()[:4] == b"\x89PNG" and (tmp_path / "axes" / "plan-calls.png").exists()
    assert f"| {LAYOUT_LABEL} | 3 | **4 ± 4.968 (3)** | 1 ± 0 (3) |" in printed
    text = md.read_text()
    assert "Settings selected on training layouts 1000-1001" in text
    assert f"| {LAYOUT_LABEL} | voot | omega=0.1 | 3 layouts, 6 runs |" in text
    # the same with the layouts named, and without any: every layout pooled, same-seed rule
    assert main(["plot", str(out), "--tuning-layouts", "1000:1002"]) == 0
    assert "**4 ± 4.968 (3)**" in capsys.readouterr().out
    assert main(["plot", str(out)]) == 0
    assert f"| {LAYOUT_LABEL} | voot | omega=0.3 | 5 layouts, 10 runs |" in capsys.readouterr().out
    assert main(["claims", str(out), "--heldout"]) == 0
    assert "judged on the held-out layouts" in capsys.readouterr().out
    # errors: both options; --heldout on a store without a family that has a held-out set
    assert main(["plot", str(out), "--heldout", "--tuning-layouts", "1000:1002"]) == 2
    assert "not both" in capsys.readouterr().err
    assert main(["plot", str(out), "--tuning-layouts", "0:3", "1000:1002"]) == 2  # none held out
    assert "every layout of the store (0-2, 1000-1001) is a tuning layout" in (
        capsys.readouterr().err
    )
    plain = tmp_path / "plain"
    assert main(["plan", "--out", str(plain), *PLAN_TINY]) == 0
    capsys.readouterr()
    assert main(["plot", str(plain), "--heldout"]) == 2
    assert "--heldout: no runs on the layouts of a family" in capsys.readouterr().err


def _layout_store(tmp_path: Path) -> Path:
    from plan_fixtures import layout_rows

    from voot.bench.store.result_store import ResultStore

    out = tmp_path / "heldout"
    store = ResultStore(out)
    for r in layout_rows():
        store.write(r)
    return out


@pytest.mark.parametrize("command", ["claims", "plot"])
def test_tuning_layouts_the_store_cannot_split_are_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], command: str
) -> None:
    """As --tuning-seeds: tuning layouts the store lacks, or covering all its layouts."""
    from cli_fixtures import assert_refused

    out = str(_layout_store(tmp_path))
    md = ["--markdown", str(tmp_path / "t.md")]
    assert_refused(
        [command, out, "--tuning-layouts", "0:3", "1000:1002", *md],
        tmp_path,
        capsys,
        "--tuning-layouts: every layout of the store (0-2, 1000-1001) is a tuning layout",
    )
    assert_refused(
        [command, out, "--tuning-layouts", "500:510", *md],
        tmp_path,
        capsys,
        "no runs on the tuning layouts 500-509 in the store (its layouts: 0-2, 1000-1001)",
    )
    assert main([command, out, "--tuning-layouts", "1000:1002", *md]) == 0  # a real split


@pytest.mark.parametrize("command", ["claims", "plot"])
def test_report_outputs_under_a_file_are_refused_before_the_report(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], command: str
) -> None:
    from cli_fixtures import assert_refused

    out = str(_layout_store(tmp_path))
    (tmp_path / "file").write_text("x")
    bad = str(tmp_path / "file" / "t")
    assert_refused(
        [command, out, "--markdown", bad], tmp_path, capsys, "--markdown", "not a folder"
    )
    if command == "plot":
        for option in ("--png", "--png-seconds", "--axes-dir"):
            assert_refused([command, out, option, bad], tmp_path, capsys, option, "not a folder")
