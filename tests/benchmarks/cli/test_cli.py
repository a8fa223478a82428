"""Tests of voot.bench.cli.main: the dispatcher (every command and measurement registered with
a parser and its --help, in the order of the help; the measurements' old spellings; the
version), errors as one line and exit status 2, the seed options, the console script."""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

import voot
from voot.bench.cli.main import COMMANDS, MEASUREMENTS, build_parser, main, measurement_names

#: The researcher's commands in the order ``voot-bench --help`` lists them.
RESEARCH = (
    "demo record-demo figure5 demo-voo env-figures bbfo plan ablation select plot claims"
    " difficulty ladder compact shipped export leaderboard measure"
).split()
#: The measurements in the order ``voot-bench measure --help`` lists them.
MEASURE = (
    "speed voo-speed overhead record-overhead memory root-parallel store-speed env-speed"
    " mesh-speed footprint-speed domain-ablation speedup"
).split()


def listed_commands(argv: list[str], capsys: pytest.CaptureFixture[str]) -> list[str]:
    """The commands the help of ``voot-bench ARGV --help`` lists."""
    with pytest.raises(SystemExit) as done:
        main([*argv, "--help"])
    assert done.value.code == 0
    return re.findall(r"^    (\S+)", capsys.readouterr().out, flags=re.MULTILINE)


def test_the_commands_in_the_order_of_the_help(capsys: pytest.CaptureFixture[str]) -> None:
    assert len(COMMANDS) == 8 and len(MEASUREMENTS) == 3
    assert listed_commands([], capsys) == RESEARCH
    assert listed_commands(["measure"], capsys) == MEASURE
    assert measurement_names(build_parser()) == MEASURE


@pytest.mark.parametrize(
    "argv", [[name] for name in RESEARCH if name != "measure"] + [["measure", m] for m in MEASURE]
)
def test_every_command_has_a_parser_with_help_and_a_handler(
    argv: list[str], capsys: pytest.CaptureFixture[str]
) -> None:
    parser = build_parser()
    for word in argv:
        (sub,) = [a for a in parser._actions if isinstance(a, argparse._SubParsersAction)]
        parser = sub.choices[word]
    assert callable(parser.get_default("func"))
    with pytest.raises(SystemExit) as done:
        main([*argv, "--help"])
    out = capsys.readouterr().out
    assert done.value.code == 0 and out.startswith(f"usage: voot-bench {' '.join(argv)} ")
    assert not re.search(r"\bissues? \d", out)  # no internal issue numbers in the help


@pytest.mark.parametrize("name", MEASURE)
def test_a_measurement_without_measure_is_the_same_command(
    name: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit):
        main([name, "--help"])
    old = capsys.readouterr().out
    with pytest.raises(SystemExit):
        main(["measure", name, "--help"])
    assert old == capsys.readouterr().out and name not in listed_commands([], capsys)


ROOT = Path(__file__).resolve().parents[3]


def test_every_command_the_docs_name_is_registered() -> None:
    """Every ``voot-bench NAME`` in the code of the README and docs/ (a code span or a line
    of a code block) is a command, and every ``voot-bench measure NAME`` a measurement (the
    docs spell measurements with ``measure``)."""
    pages = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]
    named = [
        (page.name, m.group(1), m.group(2))
        for page in pages
        for m in re.finditer(
            r"(?:^|`)(?:nice )?voot-bench ([a-z][\w-]*)(?: ([a-z][\w-]*))?",
            page.read_text(),
            flags=re.MULTILINE,
        )
    ]
    assert len(named) > 50
    for page, first, second in named:
        assert first in RESEARCH, (page, first)
        if first == "measure":
            assert second is None or second in MEASURE, (page, second)


def test_version(capsys: pytest.CaptureFixture[str]) -> None:
    with pytest.raises(SystemExit) as done:
        main(["--version"])
    assert done.value.code == 0 and capsys.readouterr().out == f"voot-bench {voot.__version__}\n"


def test_an_interrupt_is_exit_status_130(
    monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    from voot.bench.cli import measure as cli_measure

    def interrupted(args: object) -> int:
        raise KeyboardInterrupt

    monkeypatch.setattr(cli_measure, "cmd_speed", interrupted)
    assert main(["measure", "speed"]) == 130
    assert "interrupted; finished runs are saved" in capsys.readouterr().err


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["bbfo", "--functions", "nope"], "unknown function 'nope'; valid functions are:"),
        (["bbfo", "--methods", "vooo"], "unknown method 'vooo'; valid methods are:"),
        (["bbfo", "--seeds", "5:2"], "inverted or empty range '5:2'"),
        (["bbfo", "--seeds", "0"], "--seeds: need at least 1"),
        (["bbfo", "--dims", "x"], "--dims: 'x' is not an integer"),
        (["bbfo", "--budget-scale", "-1"], "budget_scale must be > 0"),
        (["bbfo", "--budget-scale", "inf"], "budget_scale must be > 0"),
        (["bbfo", "--methods", "rembo", "--dims", "3"], "the grid is empty"),
        (["plot", "/nonexistent/store"], "no voot result store here"),
        (["plot", "x", "--log"], "--log needs --regret"),
        (["bbfo", "--instance", "-1"], "instance must be an integer >= 0"),
        (["demo-voo", "--function", "nope"], "unknown function 'nope'"),
        (["measure", "speed", "--cases", "voo"], "--cases: 'voo' is not METHOD:N"),
        # once a traceback, and silence
        (["bbfo", "--budget-scale", "inf"], "budget_scale must be > 0 and finite"),
        (
            ["plan", "--problems", "shekel_chain", "--env-kwargs", "dim=5"],
            "--env-kwargs ['dim'] apply to gymnasium environments",
        ),
        (["plan", "--problems", "nope"], "unknown problem 'nope'"),
        (["plan", "--planners", "vooot"], "unknown planner 'vooot'; valid planners are:"),
        (["plan", "--set", "omega"], "--set: 'omega' is not NAME=VALUE"),
        (["plan", "--set", "depth_limit=0"], "depth_limit must be an integer >= 1"),
        (["plan", "--address", "auto"], "--address and --max-tries go with --backend ray"),
        (["plan", "--record", "r.rrd", "--backend", "ray"], "--record writes .rrd files"),
        (["plan", "--simulations", "0"], "simulations must be integers >= 1"),
        (["plan", "--seeds", "3:1"], "inverted or empty range"),
    ],
)
def test_clear_errors(argv: list[str], message: str, capsys: pytest.CaptureFixture[str]) -> None:
    """A user error is one line and exit status 2 (a sweep's with --dry-run: it runs nothing)."""
    assert main([*argv, "--dry-run"] if argv[0] in ("bbfo", "plan") else argv) == 2
    err = capsys.readouterr().err
    assert err.startswith("voot-bench: error: ") and message in err


@pytest.mark.parametrize(
    ("argv", "out", "err"),
    [
        (
            ["bbfo", "--functions", "shekel", "--methods", "voo", "--seeds", "3"],
            ["shekel-20D budget 5000: voo 18", "shekel-3D budget 500"],
            "54 runs",
        ),
        (
            ["plan", "--problems", "kitchen", "conveyor", "--grid", "default"],
            [
                "kitchen 2000 simulations, 20 seeds: voot 20, rand_doot 20",
                "conveyor 3000 simulations, 50 seeds",
            ],
            "350 runs",
        ),
    ],
)
def test_a_dry_run_lists_the_runs(
    argv: list[str], out: list[str], err: str, capsys: pytest.CaptureFixture[str]
) -> None:
    assert main([*argv, "--dry-run"]) == 0
    cap = capsys.readouterr()
    assert all(line in cap.out for line in out) and err in cap.err


SEEDED = ["demo-voo", "demo", "record-demo", "figure5", "difficulty", "ladder"]


@pytest.mark.parametrize(
    "command",
    [[c] for c in SEEDED]
    + [["measure", m] for m in ("speed", "voo-speed", "overhead", "record-overhead", "memory")]
    + [["measure", "env-speed"]],
)
@pytest.mark.parametrize("seed", ["-1", "1.5", "x"])
def test_every_seed_option_is_checked_by_the_parser(
    command: list[str], seed: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main([*command, "--seed", seed])
    assert exit_info.value.code == 2
    err = capsys.readouterr().err
    assert f"argument --seed: must be an integer >= 0, got '{seed}'" in err


@pytest.mark.parametrize(
    ("command", "option"),
    [
        ("plan", "--tuning-seeds"),
        ("plan", "--estimate"),
        ("plot", "plan-cpu-seconds.png"),
        ("claims", "--markdown"),
    ],
)
def test_protocol_options_in_the_help(
    command: str, option: str, capsys: pytest.CaptureFixture[str]
) -> None:
    with pytest.raises(SystemExit) as done:
        main([command, "--help"])
    text = " ".join(capsys.readouterr().out.split()).replace("- ", "-")  # undo the wrapping
    assert done.value.code == 0 and option in text


SCRIPT = shutil.which("voot-bench", path=str(Path(sys.executable).parent))


@pytest.mark.skipif(SCRIPT is None, reason="console script not installed")
def test_console_script_help() -> None:
    assert SCRIPT is not None
    done = subprocess.run([SCRIPT, "--help"], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0
    for command in ("demo", "demo-voo", "bbfo", "plan", "plot", "measure", "select"):
        assert command in done.stdout


# ----- a generative fuzz of the options of the generated families (issue 34) -------------
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

#: Layout seeds and levels as a user might type them, good and bad.
_SEED_TEXT = st.one_of(
    st.integers(-3, 12).map(str),
    st.sampled_from(["1.5", "1.0", "true", "abc", '"1"', "null", "9223372036854775808", "1e3"]),
)
_RANGE_TEXT = st.one_of(
    st.integers(-2, 6).map(str),
    st.tuples(st.integers(-2, 8), st.integers(-2, 8)).map(lambda t: f"{t[0]}:{t[1]}"),
    st.sampled_from(
        ["0:2,5", "x", "1:2:3", "", "1000:1002", "9223372036854775807:9223372036854775808"]
    ),
)
_LEVEL = st.sampled_from(["easy", "medium", "hard", "extreme", "EASY", ""])
_FAMILY = st.sampled_from(
    ["generated_storage", "conveyor_v2", "generated_kitchen", "conveyor_v1", "nosuch"]
)


def _option(name: str, values: st.SearchStrategy[str]) -> st.SearchStrategy[list[str]]:
    """``[]`` or ``[name, value]``."""
    return st.one_of(st.just([]), values.map(lambda v: [name, v]))


def _outputs(tmp: Path, option: str) -> st.SearchStrategy[list[str]]:
    """An output option: absent, fine, under a regular file, or the file itself."""
    return st.sampled_from(
        [[], [option, str(tmp / "ok" / "o.md")], [option, str(tmp / "file" / "o.md")]]
    )


def _check_refused_or_accepted(
    argv: list[str], tmp: Path, capsys: Any, writes: bool, must_refuse: bool = False
) -> None:
    """The property: exit 0 (accepted), or exit 2 with one ``error`` line, no traceback and
    every file under ``tmp`` as it was (``writes``: an accepted command may write).
    ``must_refuse``: the request is known to be bad (the test's own oracle), so it must be
    refused: a dry run that lists it would be a sweep of failed runs."""
    from cli_fixtures import tree_snapshot

    before = tree_snapshot(tmp)
    try:
        status = main(argv)
    except SystemExit as exc:  # argparse's own refusal (a malformed option)
        status = exc.code if isinstance(exc.code, int) else 1
    err = capsys.readouterr().err
    assert "Traceback" not in err, (argv, err)
    assert status in (0, 2), (argv, status, err)
    assert status == 2 or not must_refuse, ("accepted a bad request", argv)
    if status == 2:
        assert err.strip().splitlines()[-1].split(": error: ")[0] in (
            "voot-bench",
            f"voot-bench {argv[0]}",
        ), (argv, err)
    if status == 2 or not writes:
        assert tree_snapshot(tmp) == before, (argv, err)


@pytest.fixture(scope="module")
def fuzz_dir(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A folder with a regular file (``file``) to put outputs under, and a store of runs on
    layouts (``heldout``) for ``claims``."""
    from plan_fixtures import layout_rows

    from voot.bench.store.result_store import ResultStore

    tmp = tmp_path_factory.mktemp("fuzz")
    (tmp / "file").write_text("x")
    store = ResultStore(tmp / "heldout")
    for r in layout_rows():
        store.write(r)
    store.load(status="ok", arrays=True)
    return tmp


_FUZZ = settings(
    max_examples=25,
    deadline=None,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)


@_FUZZ
@given(data=st.data())
def test_fuzz_plan_options_of_the_generated_families(
    fuzz_dir: Path, capsys: pytest.CaptureFixture[str], data: st.DataObject
) -> None:
    tmp = fuzz_dir
    argv = ["plan", "--dry-run", "--planners", "voot", "--simulations", "2"]
    family = data.draw(_FAMILY)
    argv += ["--problems", family]
    kwargs = data.draw(
        st.lists(
            st.one_of(
                _SEED_TEXT.map(lambda v: f"layout_seed={v}"),
                _LEVEL.map(lambda v: f"difficulty={v}"),
            ),
            max_size=2,
        )
    )
    argv += ["--env-kwargs", *kwargs] if kwargs else []
    layout_seeds = data.draw(_option("--layout-seeds", _RANGE_TEXT))
    argv += layout_seeds
    argv += data.draw(_option("--seeds", st.sampled_from(["1", "0:2", "5:6"])))
    argv += ["--out", data.draw(st.sampled_from([str(tmp / "s"), str(tmp / "file" / "s")]))]
    argv += data.draw(
        st.sampled_from(
            [[], ["--record", str(tmp / "r.rrd")], ["--record", str(tmp / "file" / "r.rrd")]]
        )
    )
    # the oracle of a bad request: a layout seed that is not a plain integer >= 0, a
    # level the families do not have, layouts of an env without them, an output under a file
    bad_seed = any(
        k.startswith("layout_seed=") and not k.split("=", 1)[1].isdigit() for k in kwargs
    )
    bad_level = any(
        k.startswith("difficulty=") and k.split("=", 1)[1] not in ("easy", "medium", "hard")
        for k in kwargs
    )
    no_layouts = family == "conveyor_v1" and (
        bool(layout_seeds) or any(k.startswith("layout_seed=") for k in kwargs)
    )
    under_file = str(tmp / "file" / "") in " ".join(argv)
    must_refuse = bad_seed or bad_level or no_layouts or under_file
    _check_refused_or_accepted(argv, tmp, capsys, writes=False, must_refuse=must_refuse)


@_FUZZ
@given(data=st.data())
def test_fuzz_ablation_options(
    fuzz_dir: Path, capsys: pytest.CaptureFixture[str], data: st.DataObject
) -> None:
    tmp = fuzz_dir
    argv = ["ablation", "--dry-run", "--out", str(tmp / "a")]
    simulations = data.draw(_option("--simulations", st.integers(-6, 3).map(str)))
    argv += simulations
    problems = data.draw(
        st.lists(
            st.sampled_from(["kitchen_v1", "conveyor_v1", "kitchen_v2", "kitchen"]), max_size=2
        )
    )
    argv += ["--problems", *problems] if problems else []
    switches = data.draw(
        st.lists(
            st.sampled_from(["v1", "commit_10", "kappa_off", "authors_commit_10", "bad"]),
            max_size=2,
        )
    )
    argv += ["--switches", *switches] if switches else []
    argv += data.draw(_option("--seeds", _RANGE_TEXT))
    argv += data.draw(_option("--tuning-seeds", _RANGE_TEXT))
    markdown = data.draw(_outputs(tmp, "--markdown"))
    argv += markdown
    # the oracle: a budget below 1; --markdown without --table; a problem the switches are
    # not defined on (kitchen_v2, the v0 kitchen) with any switch but the v1 defaults alone
    named = set(switches) - {"v1"}
    off_domain = bool({"kitchen_v2", "kitchen"} & set(problems)) and (bool(named) or not switches)
    too_few = bool(simulations) and int(simulations[1]) < 1
    must_refuse = too_few or bool(markdown) or off_domain
    _check_refused_or_accepted(argv, tmp, capsys, writes=False, must_refuse=must_refuse)


@_FUZZ
@given(data=st.data())
def test_fuzz_ladder_options(
    fuzz_dir: Path,
    capsys: pytest.CaptureFixture[str],
    monkeypatch: pytest.MonkeyPatch,
    data: st.DataObject,
) -> None:
    """Only the options are checked: the ladder's measurement is replaced by a stand-in
    (the refusals come before it; its own tests measure it)."""
    from voot.bench.protocol import ladder

    monkeypatch.setattr(ladder, "ladder_report", lambda *args, **kwargs: "(ladder)")
    tmp = fuzz_dir
    argv = ["ladder"]
    argv += data.draw(
        _option(
            "--env",
            st.sampled_from(
                ["generated_kitchen", "kitchen_v2", "kitchen_v1", "CartPole-v1", "nosuch"]
            ),
        )
    )
    levels = data.draw(st.lists(_LEVEL, max_size=2))
    argv += ["--levels", *levels] if levels else []
    argv += data.draw(_option("--layouts", _RANGE_TEXT))
    argv += data.draw(_option("--samples", st.integers(-1, 2).map(str)))
    argv += data.draw(_option("--rollouts", st.integers(-1, 2).map(str)))
    argv += data.draw(_outputs(tmp, "--markdown"))
    _check_refused_or_accepted(argv, tmp, capsys, writes=True)


@_FUZZ
@given(data=st.data())
def test_fuzz_claims_options(
    fuzz_dir: Path, capsys: pytest.CaptureFixture[str], data: st.DataObject
) -> None:
    tmp = fuzz_dir
    argv = ["claims", str(tmp / "heldout")]
    argv += data.draw(_option("--tuning-layouts", _RANGE_TEXT))
    argv += data.draw(_option("--tuning-seeds", _RANGE_TEXT))
    argv += data.draw(st.sampled_from([[], ["--heldout"]]))
    argv += data.draw(_outputs(tmp, "--markdown"))
    _check_refused_or_accepted(argv, tmp, capsys, writes=True)


# ----- accepted == canonical: a respelled request means what its canonical spelling means --


def _spell_int(n: int) -> st.SearchStrategy[str]:
    """Spellings of the integer ``n`` a user may type (Python's ``int`` takes them all):
    plain, zero-padded, signed, padded with spaces, with a digit-group underscore."""
    spellings = [str(n), f"0{n}", f"+{n}", f" {n} "]
    if n >= 10:
        spellings.append(f"{str(n)[0]}_{str(n)[1:]}")
    return st.sampled_from(spellings)


def _spell_range(start: int, stop: int) -> st.SearchStrategy[str]:
    """Spellings of the range ``start .. stop-1`` (``N`` or ``START:STOP``)."""
    pairs = st.tuples(_spell_int(start), _spell_int(stop)).map(lambda t: f"{t[0]}:{t[1]}")
    return st.one_of(pairs, _spell_int(stop)) if start == 0 else pairs


def _spell_layouts(seeds: list[int]) -> st.SearchStrategy[list[str]]:
    """Spellings of the layout seeds ``seeds`` (ascending, distinct) as ``--layout-seeds``
    values: a range when they are consecutive, or a list of two or more items (one item
    ``N`` means 0 .. N-1) in any order, with repeats, spread over arguments or joined by
    commas."""
    options: list[st.SearchStrategy[list[str]]] = []
    if seeds == list(range(seeds[0], seeds[-1] + 1)):
        options.append(_spell_range(seeds[0], seeds[-1] + 1).map(lambda s: [s]))

    @st.composite
    def listed(draw: st.DrawFn) -> list[str]:
        items = seeds + draw(
            st.lists(st.sampled_from(seeds), min_size=max(0, 2 - len(seeds)), max_size=2)
        )
        items = draw(st.permutations(items))
        words = [draw(_spell_int(s)).strip() for s in items]
        cut = draw(st.integers(0, len(words)))
        head, tail = words[:cut], words[cut:]
        return head + ([",".join(tail)] if tail else [])

    options.append(listed())
    return st.one_of(options)


#: Spellings of an env keyword's JSON value that are not JSON's own integer (a string, a
#: float, a bool, a signed or padded number): the families must refuse them, never read
#: them as the integer they resemble.
def _spell_json_int(n: int) -> st.SearchStrategy[str]:
    return st.sampled_from([str(n), f" {n}", f"0{n}", f"+{n}", f"{n}.0", f'"{n}"', f"{n}e0"])


def _canonical_layouts(seeds: list[int]) -> list[str]:
    """The canonical ``--layout-seeds`` of ``seeds``: START:STOP if consecutive, else the
    seeds in order."""
    if seeds == list(range(seeds[0], seeds[-1] + 1)):
        return [f"{seeds[0]}:{seeds[-1] + 1}"]
    return [str(s) for s in seeds]


def _requested(argv: list[str], capsys: Any) -> list[Any] | None:
    """The runs ``argv`` asks for (sorted), or None if it is refused. The work never
    starts: ``plan --dry-run`` stops at its summary and ``ablation`` at the tuned run,
    both replaced by stand-ins that record the specs (see the fixture
    ``capture_requests``)."""
    _CAPTURED.clear()
    try:
        status = main(argv)
    except SystemExit as exc:
        status = exc.code if isinstance(exc.code, int) else 1
    err = capsys.readouterr().err
    assert "Traceback" not in err, (argv, err)
    assert status in (0, 2), (argv, status, err)
    if status == 2:
        return None
    assert len(_CAPTURED) == 1, argv
    return sorted(_CAPTURED[0], key=repr)


_CAPTURED: list[list[Any]] = []


@pytest.fixture
def capture_requests(monkeypatch: pytest.MonkeyPatch) -> None:
    """``plan --dry-run``'s summary and ``ablation``'s tuned run record their specs
    instead (the options are all checked and the envs made before either)."""
    from voot.bench.cli import ablation
    from voot.bench.sweep import plan

    def summary(specs: Any) -> str:
        _CAPTURED.append(list(specs))
        return ""

    def tuned(args: Any, tuning: Any, evaluation: Any) -> int:
        _CAPTURED.append([("tuning", s) for s in tuning] + [("eval", s) for s in evaluation])
        return 0

    monkeypatch.setattr(plan, "summarize_plan_specs", summary)
    monkeypatch.setattr(ablation, "plan_tuned", tuned)


_CANON = settings(
    max_examples=20,
    deadline=None,
    derandomize=True,
    suppress_health_check=[HealthCheck.function_scoped_fixture, HealthCheck.too_slow],
)


@_CANON
@given(data=st.data())
def test_fuzz_an_accepted_plan_request_is_its_canonical_one(
    fuzz_dir: Path, capsys: pytest.CaptureFixture[str], capture_requests: None, data: st.DataObject
) -> None:
    """Any spelling of a ``plan`` request the command line accepts asks for exactly the
    runs of its canonical spelling: numbers with padding, signs or underscores, seed and
    layout ranges as ``N``, ``START:STOP`` or lists in any order with repeats, a single
    layout as an env keyword, levels quoted or spaced, lists split by commas. An env
    keyword's non-integer spelling of a layout seed must be refused."""
    family = data.draw(st.sampled_from(["generated_storage", "generated_kitchen"]))
    level = data.draw(st.sampled_from(["easy", "medium"]))
    layouts = sorted(data.draw(st.sets(st.integers(0, 3), min_size=1, max_size=3)))
    seeds = data.draw(st.tuples(st.integers(0, 2), st.integers(1, 2)))
    start, stop = seeds[0], seeds[0] + seeds[1]
    simulations = data.draw(st.integers(1, 12))
    planners = data.draw(st.sets(st.sampled_from(["voot", "pw_uct"]), min_size=1))
    out = ["--out", str(fuzz_dir / "canonical")]
    canonical = ["plan", "--dry-run", "--problems", family, *out]
    canonical += ["--planners", *sorted(planners), "--simulations", str(simulations)]
    canonical += ["--seeds", f"{start}:{stop}", "--env-kwargs", f"difficulty={level}"]
    canonical += ["--layout-seeds", *_canonical_layouts(layouts)]
    expected = _requested(canonical, capsys)
    assert expected, canonical  # the canonical request is a valid one

    words = data.draw(st.permutations(sorted(planners) * data.draw(st.integers(1, 2))))
    spelled = ["plan", "--dry-run", "--problems", family, *out]
    spelled += ["--planners", *(words if data.draw(st.booleans()) else [",".join(words)])]
    spelled += ["--simulations", data.draw(_spell_int(simulations))]
    spelled += ["--seeds", data.draw(_spell_range(start, stop))]
    kwargs = [data.draw(st.sampled_from([f"difficulty={level}", f'difficulty="{level}"']))]
    json_seed = None
    if len(layouts) == 1 and data.draw(st.booleans()):
        json_seed = data.draw(_spell_json_int(layouts[0]))
        kwargs.append(f"layout_seed={json_seed}")
    else:
        spelled += ["--layout-seeds", *data.draw(_spell_layouts(layouts))]
    spelled += ["--env-kwargs", *(kwargs if data.draw(st.booleans()) else [",".join(kwargs)])]
    got = _requested(spelled, capsys)
    if json_seed is not None and json_seed.strip() != str(layouts[0]):
        assert got is None, ("a non-integer layout seed was accepted", spelled)
    else:
        assert got == expected, (spelled, canonical)


@_CANON
@given(data=st.data())
def test_fuzz_an_accepted_ablation_request_is_its_canonical_one(
    fuzz_dir: Path, capsys: pytest.CaptureFixture[str], capture_requests: None, data: st.DataObject
) -> None:
    """The same for ``ablation``: budgets, seed ranges, switch and problem lists (in any
    order, split by commas, with repeats) mean what their canonical spelling means."""
    problems = sorted(
        data.draw(st.sets(st.sampled_from(["kitchen_v1", "conveyor_v1"]), min_size=1))
    )
    switches = sorted(
        data.draw(
            st.sets(st.sampled_from(["commit_10", "kappa_off", "authors_commit_10"]), max_size=2)
        )
    )
    simulations = data.draw(st.integers(1, 12))
    tuning = data.draw(st.tuples(st.integers(0, 2), st.integers(1, 2)))
    evaluation = (tuning[0] + tuning[1] + 1, tuning[0] + tuning[1] + 2)
    out = ["--out", str(fuzz_dir / "ablation-canonical")]
    canonical = [
        "ablation",
        "--dry-run",
        *out,
        "--problems",
        *problems,
        "--simulations",
        str(simulations),
    ]
    canonical += ["--tuning-seeds", f"{tuning[0]}:{tuning[0] + tuning[1]}"]
    canonical += ["--seeds", f"{evaluation[0]}:{evaluation[1]}"]
    canonical += ["--switches", *switches] if switches else []
    expected = _requested(canonical, capsys)

    def listed(names: list[str]) -> list[str]:
        words = data.draw(st.permutations(names * data.draw(st.integers(1, 2))))
        return words if data.draw(st.booleans()) else [",".join(words)]

    spelled = ["ablation", "--dry-run", *out, "--problems", *listed(problems)]
    spelled += ["--simulations", data.draw(_spell_int(simulations))]
    spelled += ["--tuning-seeds", data.draw(_spell_range(tuning[0], tuning[0] + tuning[1]))]
    spelled += ["--seeds", data.draw(_spell_range(*evaluation))]
    spelled += ["--switches", *listed(switches)] if switches else []
    got = _requested(spelled, capsys)
    if expected is None:  # a combination the ablation refuses: refused however spelled
        assert got is None, (spelled, canonical)
    else:
        assert got == expected, (spelled, canonical)
