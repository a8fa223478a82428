"""What the docs scripts that draw figures from recordings share (a helper, not a script):
the figures folder, their command line (a scratch folder and ``--no-viewer``) and
shrinking a PNG screenshot before it is committed."""

from __future__ import annotations

import argparse
from pathlib import Path

from PIL import Image

#: Where the docs' figures go (the scripts run from the repository root).
FIGURES = Path("docs/figures")


def figure_options(doc: str, work: str, screenshots: str = "screenshots") -> tuple[Path, bool]:
    """Parse the command line of the script whose docstring is ``doc``: ``--work`` (its
    scratch folder, default ``work``) and ``--no-viewer`` (skip the viewer ``screenshots``).
    Returns the scratch folder and whether to take the screenshots; :data:`FIGURES` is
    created."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("--work", default=work, help="scratch folder")
    parser.add_argument("--no-viewer", action="store_true", help=f"skip the viewer {screenshots}")
    args = parser.parse_args()
    FIGURES.mkdir(parents=True, exist_ok=True)
    return Path(args.work), not args.no_viewer


def shrink(path: Path, width: int | None = None) -> None:
    """Scale a PNG down to ``width`` pixels wide (if wider; in place) and quantise it to
    save space."""
    img = Image.open(path).convert("RGB")
    if width is not None and img.width > width:
        img = img.resize((width, round(img.height * width / img.width)), Image.LANCZOS)
    img.quantize(colors=256, method=Image.Quantize.MEDIANCUT).save(path, optimize=True)
