"""The import graph of voot's own modules, and its cycles.

Every module under the folders of ``[tool.setuptools] package-dir`` in pyproject.toml
(``voot/``, ``envs/``, ``benchmarks/``, ``models/``) gets its import name from its path by
that table. An edge ``a -> b`` is any ``import``/``from ... import`` in ``a`` of a voot
module ``b``, at any depth (inside functions too: such an import still ties the two
modules together), except inside ``if TYPE_CHECKING:`` blocks. ``from pkg import name``
imports the module ``pkg.name`` if there is one, else ``pkg``; relative imports are
resolved against the importing module's package.

A cycle is a strongly connected component of more than one module, or a module that
imports itself. ``tests/test_import_cycles.py`` asserts there is none; run this file to
list them::

    python tools/import_cycles.py          # prints each cycle; exit status 1 if any
    python tools/import_cycles.py voot.bench   # only the cycles inside voot.bench
"""

from __future__ import annotations

import ast
import sys
import tomllib
from collections import deque
from collections.abc import Iterable, Iterator, Mapping
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: An import graph: module -> the voot modules it imports.
Graph = dict[str, set[str]]


def module_files(root: Path = ROOT) -> dict[str, Path]:
    """Import name -> file of every module of the package-dir table's folders."""
    table = tomllib.loads((root / "pyproject.toml").read_text())["tool"]["setuptools"]
    out: dict[str, Path] = {}
    for package, folder in table["package-dir"].items():
        base = root / folder
        for path in sorted(base.rglob("*.py")):
            parts = list(path.relative_to(base).with_suffix("").parts)
            if "__pycache__" in parts or any(not p.isidentifier() for p in parts):
                continue
            if parts[-1] == "__init__":
                parts.pop()
            out[".".join([package, *parts])] = path
    return out


def _is_type_checking(test: ast.expr) -> bool:
    """Whether an ``if`` test is ``TYPE_CHECKING`` (or ``typing.TYPE_CHECKING``)."""
    if isinstance(test, ast.Name):
        return test.id == "TYPE_CHECKING"
    return isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"


def _import_nodes(tree: ast.AST) -> Iterator[ast.Import | ast.ImportFrom]:
    """Every import node of ``tree`` outside ``if TYPE_CHECKING:`` bodies."""
    stack: list[ast.AST] = [tree]
    while stack:
        node = stack.pop()
        if isinstance(node, ast.Import | ast.ImportFrom):
            yield node
        if isinstance(node, ast.If) and _is_type_checking(node.test):
            stack.extend(node.orelse)
            continue
        stack.extend(ast.iter_child_nodes(node))


def _resolve(module: str, is_package: bool, node: ast.ImportFrom) -> str:
    """The absolute name ``from`` imports from (relative imports resolved)."""
    if not node.level:
        return node.module or ""
    package = module.split(".") if is_package else module.split(".")[:-1]
    base = package[: len(package) - node.level + 1]
    return ".".join(base + ([node.module] if node.module else []))


def _known(name: str, modules: Mapping[str, Path]) -> str | None:
    """``name`` if it is a module, else its longest prefix that is one (None if none)."""
    parts = name.split(".")
    while parts:
        candidate = ".".join(parts)
        if candidate in modules:
            return candidate
        parts.pop()
    return None


def imports_of(module: str, path: Path, modules: Mapping[str, Path]) -> set[str]:
    """The voot modules ``module`` (at ``path``) imports."""
    tree = ast.parse(path.read_text(), str(path))
    is_package = path.name == "__init__.py"
    out: set[str] = set()
    for node in _import_nodes(tree):
        if isinstance(node, ast.Import):
            targets = [alias.name for alias in node.names]
        else:
            base = _resolve(module, is_package, node)
            targets = [
                f"{base}.{alias.name}" if f"{base}.{alias.name}" in modules else base
                for alias in node.names
            ]
        for target in targets:
            known = _known(target, modules)
            if known is not None:
                out.add(known)
    return out


def import_graph(root: Path = ROOT) -> Graph:
    """The import graph of every voot module (see the module's docstring)."""
    modules = module_files(root)
    return {name: imports_of(name, path, modules) for name, path in modules.items()}


def components(graph: Mapping[str, Iterable[str]]) -> list[list[str]]:
    """The strongly connected components of ``graph`` (Tarjan's algorithm, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    on_stack: set[str] = set()
    stack: list[str] = []
    out: list[list[str]] = []
    for start in sorted(graph):
        if start in index:
            continue
        work: list[tuple[str, Iterator[str]]] = [(start, iter(sorted(graph.get(start, ()))))]
        index[start] = low[start] = len(index)
        stack.append(start)
        on_stack.add(start)
        while work:
            node, children = work[-1]
            child = next(children, None)
            if child is not None:
                if child not in index:
                    index[child] = low[child] = len(index)
                    stack.append(child)
                    on_stack.add(child)
                    work.append((child, iter(sorted(graph.get(child, ())))))
                elif child in on_stack:
                    low[node] = min(low[node], index[child])
                continue
            work.pop()
            if work:
                parent = work[-1][0]
                low[parent] = min(low[parent], low[node])
            if low[node] == index[node]:
                component = []
                while True:
                    member = stack.pop()
                    on_stack.discard(member)
                    component.append(member)
                    if member == node:
                        break
                out.append(sorted(component))
    return out


def shortest_cycle(graph: Mapping[str, Iterable[str]], start: str, within: set[str]) -> list[str]:
    """A shortest import cycle through ``start`` inside ``within`` (``[start, ..., start]``)."""
    parent: dict[str, str] = {}
    queue = deque([start])
    while queue:
        node = queue.popleft()
        for child in sorted(graph.get(node, ())):
            if child not in within:
                continue
            if child == start:
                path = [node]
                while path[-1] != start:
                    path.append(parent[path[-1]])
                return [*reversed(path), start]
            if child not in parent:
                parent[child] = node
                queue.append(child)
    return []


def cycles(graph: Mapping[str, Iterable[str]], prefix: str = "") -> list[str]:
    """One line per cycle of ``graph`` touching a module named ``prefix``...: the
    component's modules and a shortest cycle through its first one."""
    lines = []
    for component in components(graph):
        if not any(m == prefix or m.startswith(prefix) for m in component):
            continue
        if len(component) == 1:
            if component[0] in graph.get(component[0], ()):
                lines.append(f"{component[0]} imports itself")
            continue
        path = shortest_cycle(graph, component[0], set(component))
        lines.append(
            f"{len(component)} modules: {', '.join(component)}\n    e.g. {' -> '.join(path)}"
        )
    return lines


def main(argv: list[str]) -> int:
    prefix = argv[0] if argv else ""
    found = cycles(import_graph(), prefix)
    for line in found:
        print(line)
    print(f"{len(found)} import cycles" + (f" touching {prefix}" if prefix else ""))
    return 1 if found else 0


if __name__ == "__main__":
    raise SystemExit(main(sys.argv[1:]))
