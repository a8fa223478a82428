r"""Griffe extension: render the reStructuredText bits of voot's docstrings in MkDocs.

voot's docstrings are Google style (parsed by mkdocstrings) but write maths and
references the Sphinx way, which Markdown would show verbatim. Before rendering, this
extension rewrites, in every docstring:

* ``:math:`x^2``` -> ``\(x^2\)`` (inline maths for ``pymdownx.arithmatex``);
* ``:class:`Foo```, ``:func:``, ``:meth:``, ``:attr:``, ``:data:``, ``:mod:``,
  ``:exc:``, ``:obj:`` -> ```Foo``` (code; a leading ``~`` is dropped);
* a paragraph ending in ``::`` (reST literal-block marker) -> ending in ``:``;
* ``.. math::`` blocks -> ``$$ ... $$`` display maths.
"""

from __future__ import annotations

import re
from typing import Any

from griffe import Extension, Object

_MATH = re.compile(r":math:`([^`]+)`")
_ROLE = re.compile(r":(?:py:)?(?:class|func|meth|attr|data|mod|exc|obj|const):`~?([^`]+)`")
_LITERAL = re.compile(r"(\S)::[ \t]*$", re.MULTILINE)
_MATH_BLOCK = re.compile(r"^([ \t]*)\.\. math::[ \t]*\n((?:\1[ \t]+.*\n|[ \t]*\n)+)", re.MULTILINE)


def _math_block(match: re.Match[str]) -> str:
    indent, body = match.group(1), match.group(2)
    lines = [line.strip() for line in body.strip("\n").splitlines()]
    return (
        f"{indent}$$\n" + "".join(f"{indent}{line}\n" for line in lines if line) + f"{indent}$$\n\n"
    )


def rewrite(text: str) -> str:
    """The docstring ``text`` with its reST roles turned into Markdown."""
    text = _MATH_BLOCK.sub(_math_block, text if text.endswith("\n") else text + "\n").rstrip("\n")
    text = _MATH.sub(lambda m: rf"\({m.group(1)}\)", text)
    text = _ROLE.sub(lambda m: f"`{m.group(1)}`", text)
    return _LITERAL.sub(r"\1:", text)


class RstRoles(Extension):
    """Rewrite reST roles in every object's docstring (see the module docstring)."""

    def on_instance(self, *, obj: Object, **kwargs: Any) -> None:
        if obj.docstring is not None:
            obj.docstring.value = rewrite(obj.docstring.value)
