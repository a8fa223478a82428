"""Tests of ``voot-bench demo-voo`` and ``demo``."""

from __future__ import annotations

from pathlib import Path

import pytest

from voot.bench.cli.main import main


def test_demo_prints_best_optimum_and_regret(capsys: pytest.CaptureFixture[str]) -> None:
    assert main(["demo-voo", "--budget", "200", "--dim", "10"]) == 0
    out = capsys.readouterr().out
    assert "voo on shekel-10D: 200 evaluations" in out
    for word in ("best value found", "known optimum", "regret", "best after   100"):
        assert word in out


def test_demo_plans_on_the_kitchen_and_writes_a_recording(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    out = tmp_path / "demo"
    assert main(["demo", "--simulations", "5", "--seed", "0", "--no-video", "--out", str(out)]) == 0
    assert (out / "kitchen_voot.rrd").stat().st_size > 0
    assert "rerun " in capsys.readouterr().out


def test_demo_layout_options(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    from voot.bench.cli import demo as cli_demo
    from voot.bench.demos import kitchen_demo
    from voot.envs.kitchen.generated.layout import DIFFICULTIES

    # the help's copies of the levels and defaults are the library's
    assert cli_demo.DIFFICULTY_CHOICES == tuple(DIFFICULTIES)
    assert cli_demo.DEFAULT_LAYOUT_SEED == kitchen_demo.DEFAULT_LAYOUT_SEED
    assert cli_demo.DEFAULT_DIFFICULTY == kitchen_demo.DEFAULT_DIFFICULTY
    out = str(tmp_path / "demo")
    assert main(["demo", "--out", out, "--layout-seed", "3"]) == 2  # v1 is one fixed kitchen
    err = capsys.readouterr().err
    assert "--layout-seed chooses a generated kitchen" in err and "--env generated_kitchen" in err
    assert main(["demo", "--out", out, "--env", "kitchen", "--difficulty", "hard"]) == 2
    assert "--difficulty chooses" in capsys.readouterr().err
    with pytest.raises(SystemExit):
        main(["demo", "--out", out, "--env", "kitchen_v2", "--difficulty", "extreme"])
    assert not (tmp_path / "demo").exists()


def test_demo_on_a_generated_kitchen(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    out = tmp_path / "demo"
    argv = ["demo", "--env", "generated_kitchen", "--layout-seed", "2", "--difficulty", "easy"]
    assert main([*argv, "--simulations", "3", "--no-video", "--out", str(out)]) == 0
    assert (out / "kitchen_v2_easy_2_voot.rrd").stat().st_size > 0
    assert "voot/GeneratedKitchen-v0, layout_seed 2, difficulty easy" in capsys.readouterr().out


def test_demo_takes_the_old_generated_kitchen_name_with_a_warning(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import voot._registration

    monkeypatch.setattr(voot._registration, "_WARNED", set())  # it warns once per process
    argv = ["demo", "--env", "kitchen_v2", "--layout-seed", "2", "--difficulty", "easy"]
    with pytest.warns(FutureWarning, match="now voot/GeneratedKitchen-v0"):
        assert main([*argv, "--simulations", "2", "--no-video", "--out", str(tmp_path)]) == 0


def test_demo_and_figure5_default_to_the_papers_protocol() -> None:
    """Both kitchen commands default to the kitchen of the paper's protocol (v1), and
    their help lists the kitchen names the records give, by meaning."""
    from voot.bench.cli.main import build_parser
    from voot.bench.protocol.problems import names_text, normalize_problem
    from voot.problems import problem_record

    parser = build_parser()
    for command in ("demo", "figure5"):
        args = parser.parse_args([command])
        record = problem_record(normalize_problem(args.env))
        assert record.v1_rules and not record.layouts, command
    helps = {
        a.dest: a.help
        for a in parser._subparsers._group_actions[0].choices["demo"]._actions  # type: ignore[union-attr]
    }
    assert names_text("kitchen") in helps["env"]


@pytest.mark.parametrize("command", ["demo", "record-demo", "figure5"])
def test_demo_outputs_under_a_file_are_refused_before_planning(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], command: str
) -> None:
    from cli_fixtures import assert_refused

    (tmp_path / "file").write_text("x")
    bad = str(tmp_path / "file" / "out")
    assert_refused([command, "--out", bad], tmp_path, capsys, "--out", "is a file, not a folder")
    assert_refused([command, "--out", str(tmp_path / "file")], tmp_path, capsys, "not a folder")


def test_env_figures_refuses_an_output_folder_under_a_file(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    from cli_fixtures import assert_refused

    (tmp_path / "file").write_text("x")
    assert_refused(["env-figures", str(tmp_path / "file" / "f")], tmp_path, capsys, "OUT_DIR")
