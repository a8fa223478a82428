"""Tests of ``voot-bench env-figures``, the command line of voot.bench.demos.env_figures
(rendering is exercised by the docs run)."""

from __future__ import annotations

from pathlib import Path

import pytest

from voot.bench.cli.main import main
from voot.bench.demos import env_figures


def test_help_prints_help_and_renders_nothing(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.chdir(tmp_path)
    rendered: list[Path] = []
    monkeypatch.setattr(env_figures, "render_all", rendered.append)
    with pytest.raises(SystemExit) as done:
        main(["env-figures", "--help"])
    assert done.value.code == 0 and "out_dir" in capsys.readouterr().out
    assert rendered == [] and not (tmp_path / "--help").exists()
    assert main(["env-figures", "figs"]) == 0
    assert main(["env-figures"]) == 0
    assert rendered == [Path("figs"), Path("docs/figures")]
