"""argparse ``type=`` converters shared by the ``voot-bench`` commands.

They live here, not in :mod:`voot.validation`: the library checks values and raises
``ValueError``; turning a command-line string into a value and an error into argparse's
``argument --seed: ...`` message is the command line's business, so the library never
imports argparse.
"""

from __future__ import annotations

import argparse


def seed_argument(text: str) -> int:
    """An argparse ``type=`` for every ``--seed`` option: an integer >= 0.

    argparse then reports ``argument --seed: must be an integer >= 0, got '-1'``, the
    same for every command, instead of numpy's message from deep inside a run. (The
    library's own check of a seed, for any caller, is :func:`voot.validation.seed`.)
    """
    try:
        value = int(text)
    except ValueError:
        value = -1
    if value < 0:
        raise argparse.ArgumentTypeError(f"must be an integer >= 0, got {text!r}")
    return value
