"""Tests of ``voot-bench ablation`` and ``voot-bench claims --ablation``."""

from __future__ import annotations

from pathlib import Path

import pytest

from voot.bench.cli.main import main
from voot.bench.store.result_store import ResultStore


def test_list_and_dry_run(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["ablation", "--list"]) == 0
    out = capsys.readouterr().out
    assert "pw_authors" in out and "commit_off" in out and out.startswith("v1")
    args = ["ablation", "--out", "/nonexistent/ablation", "--problems", "kitchen_v1"]
    assert main([*args, "--switches", "kappa_off", "--dry-run"]) == 0
    captured = capsys.readouterr()
    # tuning: 6 settings x 5 seeds for voot, voot[kappa_off] and pw_uct
    assert "tuning: 90 runs" in captured.err and "evaluation: 60 runs" in captured.err


def test_env_kwargs_list_the_runs_on_that_domain(capsys: pytest.CaptureFixture[str]) -> None:
    args = ["ablation", "--out", "/nonexistent/ablation", "--problems", "conveyor_v1"]
    kwargs = ["--env-kwargs", "base_model=footprint", "rooms=authors"]
    assert main([*args, "--switches", "pw_authors", "--dry-run", *kwargs]) == 0
    captured = capsys.readouterr()
    # voot 6 and pw_uct 6 + pw_uct[pw_authors] 6 settings x 5 seeds; 3 x 20 evaluation runs
    assert "tuning: 90 runs" in captured.err and "evaluation: 60 runs" in captured.err
    assert "conveyor_v1(base_model=footprint, rooms=authors)" in captured.out
    assert main([*args, "--dry-run", "--env-kwargs", "rooms"]) != 0  # not NAME=VALUE
    assert "--env-kwargs: 'rooms' is not NAME=VALUE" in capsys.readouterr().err


def test_a_repeated_problem_lists_its_runs_once(capsys: pytest.CaptureFixture[str]) -> None:
    """``--problems kitchen_v1 kitchen_v1`` (or ``kitchen_v1,kitchen_v1``) is the kitchen
    once: it listed every run twice (found by the canonical-request fuzz of test_cli.py)."""
    args = ["ablation", "--out", "/nonexistent/ablation", "--switches", "kappa_off", "--dry-run"]
    for problems in (["kitchen_v1"], ["kitchen_v1", "kitchen_v1"], ["kitchen_v1,kitchen_v1"]):
        assert main([*args, "--problems", *problems]) == 0
        err = capsys.readouterr().err
        assert "tuning: 90 runs" in err and "evaluation: 60 runs" in err, (problems, err)


def test_unknown_switch_and_claims_without_tuning_seeds_are_errors(
    capsys: pytest.CaptureFixture[str],
) -> None:
    assert main(["ablation", "--switches", "pw_inverted", "--dry-run"]) != 0
    assert "valid switches are" in capsys.readouterr().err
    assert main(["claims", "docs/data/ablation-v1", "--ablation"]) != 0
    assert "--tuning-seeds" in capsys.readouterr().err


def test_a_tiny_ablation_runs_resumes_and_draws_its_table(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "abl"
    args = [
        "ablation", "--out", str(out), "--problems", "kitchen_v1", "--switches", "commit_off",
        "--seeds", "0:2", "--tuning-seeds", "1000:1001", "--simulations", "15",
        "--workers", "1", "--backend", "serial", "--no-progress",
    ]  # fmt: skip
    assert main(args) == 0
    rows = ResultStore(out, create=False).load(kind="plan", status="ok")
    variants = {r["config"].get("variant", "") for r in rows}
    assert variants == {"", "commit_off"}
    n = len(rows)
    capsys.readouterr()
    assert main(args) == 0  # resumes: nothing runs again
    assert len(ResultStore(out, create=False).load(kind="plan")) == n
    md = tmp_path / "table.md"
    assert main(["claims", str(out), "--tuning-seeds", "1000:1001", "--ablation",
                 "--markdown", str(md)]) == 0  # fmt: skip
    text = md.read_text()
    assert "| commit_off | kitchen_v1 | voot |" in text  # no data: 15 < 750 simulations
    assert "runs of 15 simulations" in text
    assert "voot[commit_off] vs pw_uct[commit_off] | no data" in text
    # plot takes a variant's label as a planner filter
    md = tmp_path / "plot.md"
    plot = [
        "plot",
        str(out),
        "--tuning-seeds",
        "1000:1001",
        "--planners",
        "voot",
        "voot[commit_off]",
    ]
    assert main([*plot, "--markdown", str(md)]) == 0
    table = md.read_text()
    assert "voot[commit_off]" in table and "pw_uct" not in table


# ----- options that would not run as asked are refused (issue 34) ------------------------
@pytest.mark.parametrize(
    ("extra", "needles"),
    [
        (["--simulations", "0"], ["--simulations must be >= 1, got 0"]),
        (["--simulations", "-5"], ["--simulations must be >= 1, got -5"]),
        (["--problems", "kitchen_v2"], ["no ablation switch applies to voot/KitchenClearing-v2"]),
        (
            ["--problems", "kitchen_v1", "--switches", "commit_10"],
            ["commit_10 applies to voot/ConveyorPacking-v1 only"],
        ),
        (["--markdown", "t.md"], ["--markdown writes the table of --table"]),
    ],
)
def test_ablation_options_that_would_not_run_as_asked_are_refused(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], extra: list[str], needles: list[str]
) -> None:
    from cli_fixtures import assert_refused

    argv = ["ablation", "--out", str(tmp_path / "store"), "--seeds", "1", "--tuning-seeds", "5:6"]
    # the dry run first: the old code ran (or listed) these without a word
    assert_refused([*argv, *extra, "--dry-run"], tmp_path, capsys, *needles)
    assert_refused([*argv, *extra, "--workers", "1", "--no-progress"], tmp_path, capsys, *needles)


def test_ablation_switches_that_apply_somewhere_run(capsys: pytest.CaptureFixture[str]) -> None:
    from voot.bench.cli.main import main

    # commit_10 is conveyor-only: beside the kitchen it runs on the conveyor alone
    argv = ["ablation", "--switches", "commit_10", "--seeds", "1", "--tuning-seeds", "5:6"]
    assert main([*argv, "--no-baseline", "--dry-run"]) == 0
    out = capsys.readouterr().out
    assert "conveyor_v1" in out and "kitchen_v1" not in out
    # the v1 defaults alone are a valid ablation of any problem
    assert main([*argv[:1], "--switches", "v1", "--problems", "kitchen_v2", "--dry-run"]) == 0
