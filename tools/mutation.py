"""A small AST-level mutation-testing runner for the core modules.

mutmut 3 copies the tree into ``mutants/`` and imports it from there, which does not
fit this repository's package-dir mapping (``envs/`` installs as ``voot.envs``,
``benchmarks/`` as ``voot.bench``) without extra staging; this runner is simpler:
it applies one mutation at a time to a source file, runs the given test modules with
``pytest -x -q -p no:cacheprovider``, restores the file and records whether the
tests failed (killed), passed (survived) or ran past the time limit (timeout, counted
as killed).

Mutations (one per mutant, applied to the source text of a single AST node, so the
rest of the file, its comments and its line numbers are untouched):

* arithmetic operators: ``+``/``-``, ``*``/``/``, ``//`` -> ``/``, ``%`` -> ``*``,
  ``**`` -> ``*``, and the same for augmented assignments (``+=`` -> ``-=``, ...);
* comparisons: ``<``/``<=``, ``>``/``>=``, ``==``/``!=``, ``is``/``is not``,
  ``in``/``not in``;
* boolean operators: ``and``/``or``; ``not x`` -> ``x``;
* conditions of ``if``, ``while``, ``assert`` and conditional expressions negated;
* constants: ``0``/``1`` swapped, other integers ``n`` -> ``n + 1``, floats ``x`` ->
  ``x + 1.0`` (``0.0`` -> ``1.0``), ``True``/``False`` swapped (strings are left alone:
  they are messages and keys);
* ``return value`` -> ``return None``; ``break``/``continue`` swapped.

Docstrings, ``raise`` statements, f-strings and type annotations are not mutated.

Run it from the repository root with the project's virtual environment active; the
package must be installed editable (``pip install -e .``) so the tests import the
mutated file::

    python tools/mutation.py voot/optim/voo.py tests/optim/test_voo.py tests/optim/test_registry.py
    python tools/mutation.py envs/kitchen/checks.py tests/envs/kitchen/test_kitchen_checks.py \\
        --functions _pick_kinematics,_place_checks,precheck
    python tools/mutation.py benchmarks/store/result_store.py tests/benchmarks/store/test_store.py --sample 150 --seed 0

``--list`` prints the mutants without running anything; ``--only 3,17`` runs the
named mutants; ``--json out.json`` writes every result. The file is restored after
each mutant and again on exit (also on Ctrl-C). Mutants run one at a time, since
they edit the checkout in place.
"""

from __future__ import annotations

import argparse
import ast
import json
import random
import subprocess
import sys
import time
from dataclasses import asdict, dataclass
from pathlib import Path

BINOP_SWAP: dict[type, type] = {
    ast.Add: ast.Sub,
    ast.Sub: ast.Add,
    ast.Mult: ast.Div,
    ast.Div: ast.Mult,
    ast.FloorDiv: ast.Div,
    ast.Mod: ast.Mult,
    ast.Pow: ast.Mult,
}
CMP_SWAP: dict[type, type] = {
    ast.Lt: ast.LtE,
    ast.LtE: ast.Lt,
    ast.Gt: ast.GtE,
    ast.GtE: ast.Gt,
    ast.Eq: ast.NotEq,
    ast.NotEq: ast.Eq,
    ast.Is: ast.IsNot,
    ast.IsNot: ast.Is,
    ast.In: ast.NotIn,
    ast.NotIn: ast.In,
}


@dataclass
class Mutant:
    """One mutation: replace ``source[start:end]`` by ``replacement``."""

    index: int
    line: int
    start: int
    end: int
    original: str
    replacement: str
    kind: str
    function: str
    status: str = "pending"
    seconds: float = 0.0


def _offsets(source: str) -> list[int]:
    """Character offset of the start of each line (1-based line numbers -> index)."""
    starts = [0, 0]
    for line in source.splitlines(keepends=True):
        starts.append(starts[-1] + len(line))
    return starts


def _span(node: ast.AST, starts: list[int]) -> tuple[int, int]:
    # Positions are in UTF-8 bytes; the checked files are ASCII in code, so
    # characters and bytes coincide on the lines that are mutated.
    begin = starts[node.lineno] + node.col_offset  # type: ignore[attr-defined]
    end = starts[node.end_lineno] + node.end_col_offset  # type: ignore[attr-defined]
    return begin, end


class _Collector(ast.NodeVisitor):
    def __init__(self, source: str, functions: set[str] | None) -> None:
        self.source = source
        self.starts = _offsets(source)
        self.functions = functions
        self.stack: list[str] = []
        self.found: list[Mutant] = []
        self.skip: set[int] = set()

    # --- scope -----------------------------------------------------------
    def _active(self) -> bool:
        if self.functions is None:
            return True
        return any(name in self.functions for name in self.stack)

    def _function(self, node: ast.FunctionDef | ast.AsyncFunctionDef) -> None:
        self.stack.append(node.name)
        for default in node.args.defaults + [d for d in node.args.kw_defaults if d]:
            self.visit(default)
        body = node.body
        if (
            body
            and isinstance(body[0], ast.Expr)
            and isinstance(body[0].value, ast.Constant)
            and isinstance(body[0].value.value, str)
        ):
            body = body[1:]
        for stmt in body:
            self.visit(stmt)
        self.stack.pop()

    visit_FunctionDef = _function
    visit_AsyncFunctionDef = _function

    def visit_ClassDef(self, node: ast.ClassDef) -> None:
        body = node.body
        if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
            body = body[1:]
        for stmt in body:
            self.visit(stmt)

    def visit_AnnAssign(self, node: ast.AnnAssign) -> None:
        if node.value is not None:
            self.visit(node.value)

    def visit_Raise(self, node: ast.Raise) -> None:
        # raise statements (the exception and its message) are not mutated
        return

    def visit_JoinedStr(self, node: ast.JoinedStr) -> None:
        return

    # --- mutations -------------------------------------------------------
    def _add(self, node: ast.AST, replacement: str, kind: str) -> None:
        if not self._active():
            return
        begin, end = _span(node, self.starts)
        self.found.append(
            Mutant(
                index=len(self.found),
                line=node.lineno,  # type: ignore[attr-defined]
                start=begin,
                end=end,
                original=self.source[begin:end],
                replacement=replacement,
                kind=kind,
                function=self.stack[-1] if self.stack else "<module>",
            )
        )

    def _with(self, node: ast.expr, **changes: object) -> str:
        clone = ast.parse(ast.unparse(node), mode="eval").body
        for key, value in changes.items():
            setattr(clone, key, value)
        return "(" + ast.unparse(clone) + ")"

    def visit_BinOp(self, node: ast.BinOp) -> None:
        swap = BINOP_SWAP.get(type(node.op))
        if swap is not None:
            self._add(
                node, self._with(node, op=swap()), f"{type(node.op).__name__}->{swap.__name__}"
            )
        self.generic_visit(node)

    def visit_AugAssign(self, node: ast.AugAssign) -> None:
        swap = BINOP_SWAP.get(type(node.op))
        if swap is not None:
            clone = ast.parse(ast.unparse(node)).body[0]
            clone.op = swap()  # type: ignore[attr-defined]
            self._add(node, ast.unparse(clone), f"Aug{type(node.op).__name__}->{swap.__name__}")
        self.visit(node.value)

    def visit_Compare(self, node: ast.Compare) -> None:
        for i, op in enumerate(node.ops):
            swap = CMP_SWAP.get(type(op))
            if swap is None:
                continue
            ops = [type(o)() for o in node.ops]
            ops[i] = swap()
            self._add(node, self._with(node, ops=ops), f"{type(op).__name__}->{swap.__name__}")
        self.generic_visit(node)

    def visit_BoolOp(self, node: ast.BoolOp) -> None:
        swap = ast.Or if isinstance(node.op, ast.And) else ast.And
        self._add(node, self._with(node, op=swap()), f"{type(node.op).__name__}->{swap.__name__}")
        self.generic_visit(node)

    def visit_UnaryOp(self, node: ast.UnaryOp) -> None:
        if isinstance(node.op, ast.Not):
            self._add(node, "(" + ast.unparse(node.operand) + ")", "drop-not")
        elif isinstance(node.op, ast.USub) and isinstance(node.operand, ast.Constant):
            # ``-1`` is one constant to a reader; mutate it as such.
            value = node.operand.value
            if isinstance(value, int | float) and not isinstance(value, bool):
                self._add(node, repr(-value + 1), "constant")
            return
        self.generic_visit(node)

    def _negate(self, test: ast.expr) -> None:
        if isinstance(test, ast.UnaryOp) and isinstance(test.op, ast.Not):
            return  # the same mutant as drop-not
        self._add(test, "(not (" + ast.unparse(test) + "))", "negate-condition")

    def visit_If(self, node: ast.If) -> None:
        self._negate(node.test)
        self.generic_visit(node)

    def visit_While(self, node: ast.While) -> None:
        self._negate(node.test)
        self.generic_visit(node)

    def visit_IfExp(self, node: ast.IfExp) -> None:
        self._negate(node.test)
        self.generic_visit(node)

    def visit_Assert(self, node: ast.Assert) -> None:
        self._negate(node.test)
        self.visit(node.test)

    def visit_Constant(self, node: ast.Constant) -> None:
        value = node.value
        if isinstance(value, bool):
            self._add(node, repr(not value), "constant")
        elif isinstance(value, int):
            self._add(node, repr({0: 1, 1: 0}.get(value, value + 1)), "constant")
        elif isinstance(value, float):
            self._add(node, repr(value + 1.0), "constant")

    def visit_Return(self, node: ast.Return) -> None:
        if node.value is not None and not (
            isinstance(node.value, ast.Constant) and node.value.value is None
        ):
            self._add(node, "return None", "return-None")
            self.visit(node.value)

    def visit_Break(self, node: ast.Break) -> None:
        self._add(node, "continue", "break->continue")

    def visit_Continue(self, node: ast.Continue) -> None:
        self._add(node, "break", "continue->break")


def collect(path: Path, functions: set[str] | None) -> list[Mutant]:
    """Every mutant of ``path`` (inside ``functions`` if given), each checked to compile."""
    source = path.read_text()
    collector = _Collector(source, functions)
    collector.visit(ast.parse(source))
    out: list[Mutant] = []
    seen: set[tuple[int, int, str]] = set()
    for m in collector.found:
        key = (m.start, m.end, m.replacement)
        if key in seen or m.original == m.replacement:
            continue
        seen.add(key)
        mutated = source[: m.start] + m.replacement + source[m.end :]
        try:
            compile(mutated, str(path), "exec")
        except SyntaxError:
            continue
        m.index = len(out)
        out.append(m)
    return out


def run_tests(tests: list[str], timeout: float) -> tuple[str, float]:
    """Run pytest on ``tests``; ``killed`` if it fails, ``survived`` if it passes."""
    cmd = [sys.executable, "-m", "pytest", "-x", "-q", "-p", "no:cacheprovider", *tests]
    began = time.monotonic()
    try:
        done = subprocess.run(cmd, capture_output=True, timeout=timeout, check=False)
    except subprocess.TimeoutExpired:
        return "timeout", time.monotonic() - began
    # any non-zero exit (failures, errors, a crash on import) kills the mutant
    return ("survived" if done.returncode == 0 else "killed"), time.monotonic() - began


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("source", type=Path, help="file to mutate")
    parser.add_argument("tests", nargs="+", help="test modules to run for each mutant")
    parser.add_argument("--functions", help="comma-separated function names to restrict to")
    parser.add_argument("--sample", type=int, help="run a random sample of this many mutants")
    parser.add_argument("--seed", type=int, default=0, help="seed of the sample")
    parser.add_argument("--only", help="comma-separated mutant indices to run")
    parser.add_argument("--list", action="store_true", help="list the mutants and exit")
    parser.add_argument("--json", type=Path, help="write the results here")
    parser.add_argument("--timeout-factor", type=float, default=3.0)
    args = parser.parse_args(argv)

    functions = set(args.functions.split(",")) if args.functions else None
    mutants = collect(args.source, functions)
    if args.list:
        for m in mutants:
            print(
                f"{m.index:4d} L{m.line:<4d} {m.function:24s} {m.kind:18s} {m.original!r} -> {m.replacement!r}"
            )
        print(f"{len(mutants)} mutants")
        return 0
    chosen = mutants
    if args.only:
        wanted = {int(i) for i in args.only.split(",")}
        chosen = [m for m in mutants if m.index in wanted]
    elif args.sample and args.sample < len(mutants):
        chosen = sorted(
            random.Random(args.seed).sample(mutants, args.sample), key=lambda m: m.index
        )

    original = args.source.read_text()
    status, base = run_tests(args.tests, timeout=1800)
    if status != "survived":
        print("the tests fail on the unmutated source; fix that first", file=sys.stderr)
        return 2
    timeout = args.timeout_factor * base + 10
    print(f"baseline {base:.1f}s, timeout {timeout:.0f}s, {len(chosen)}/{len(mutants)} mutants")
    try:
        for m in chosen:
            args.source.write_text(original[: m.start] + m.replacement + original[m.end :])
            m.status, m.seconds = run_tests(args.tests, timeout)
            args.source.write_text(original)
            mark = "SURVIVED" if m.status == "survived" else m.status
            print(
                f"{m.index:4d} L{m.line:<4d} {m.function:20s} {m.kind:18s} {mark:8s} "
                f"{m.original!r:.60} -> {m.replacement!r:.60}",
                flush=True,
            )
    finally:
        args.source.write_text(original)
    killed = sum(m.status in ("killed", "timeout") for m in chosen)
    print(
        f"score {killed}/{len(chosen)} = {100 * killed / max(len(chosen), 1):.1f}% "
        f"({sum(m.status == 'timeout' for m in chosen)} timeouts counted as killed)"
    )
    if args.json:
        args.json.write_text(json.dumps([asdict(m) for m in chosen], indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
