"""Write the benchmark scenes ``kitchen.xml`` and ``conveyor.xml`` (run once; output committed).

``python -m voot.models.generate_scenes`` (or ``python models/generate_scenes.py`` in a
checkout) rewrites both files next to this script. The scenes and their building blocks
are the library :mod:`voot.envs.assets` (:mod:`voot.envs.assets.fixed_scenes` writes
these two with :mod:`voot.envs.assets.mjcf`, as the generated families write theirs):
edit them there, then run this.
"""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent

if __name__ == "__main__" and not __package__:  # run as a file: use this checkout's voot
    sys.path.insert(0, str(HERE.parent))

from voot.envs.assets.fixed_scenes import FIXED_SCENES  # noqa: E402


def main() -> None:
    """Write ``kitchen.xml`` and ``conveyor.xml`` next to this module."""
    for name, write in FIXED_SCENES.items():
        path = HERE / name
        path.write_text(write())
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
