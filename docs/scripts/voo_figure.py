"""Draw docs/figures/voo_voronoi_shekel2d.png: VOO's implicit Voronoi cells on a 2-D Shekel.

The picture of the paper's Figure 2 (right), made with voot's own VOO:

* left: the 2-D Shekel function and the points VOO evaluates, coloured by order;
* right: the Voronoi partition of the first points (never built by VOO; drawn here with
  scipy.spatial.Voronoi), the best cell shaded, and how ``centered_uniform`` draws from it:
  proposals from the boxes shrunk towards the best point by ``e^-k``, rejected (x) until
  one lands in the best cell (the same acceptance test as VOO's ``in_best_cell``).

The function is DEAP's own 2-D Shekel example (the figure in DEAP's documentation):
``A = [[.5, .5], [.25, .25], [.25, .75], [.75, .25], [.75, .75]]``,
``c = [.002, .005, .005, .005, .005]`` on ``[0, 1]^2``: one peak of height about 500 in the
middle, four of about 200 around it, nearly flat elsewhere. omega = 0.3 as in the
authors' 2-D visualisation script (which used the same peaks and widths both multiplied
by 500 on ``[0, 500]^2``; there the widths do not scale with the box, so the peaks become
needles about 1 unit wide and the picture shows nothing).

Run from the repository root (needs the ``bench`` extra for matplotlib)::

    python docs/scripts/voo_figure.py [--out docs/figures/voo_voronoi_shekel2d.png]
"""

from __future__ import annotations

import argparse
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.colors import LogNorm
from matplotlib.lines import Line2D
from matplotlib.patches import Patch, Polygon, Rectangle
from scipy.spatial import Voronoi

from voot.functions import make_shekel
from voot.optim import Bounds, make_optimizer
from voot.optim.voo import VOO

A = np.array([[0.5, 0.5], [0.25, 0.25], [0.25, 0.75], [0.75, 0.25], [0.75, 0.75]])
C = np.array([0.002, 0.005, 0.005, 0.005, 0.005])
BOX = Bounds.cube(0.0, 1.0, 2)
OMEGA = 0.3
SEED = 1
N_EVALS = 60  # left panel
N_CELLS = 12  # right panel: partition after this many evaluations


def voronoi_cells(points: np.ndarray, box: Bounds) -> list[np.ndarray]:
    """Polygons of the Voronoi cells of ``points`` inside the 2-D ``box``.

    Every cell is bounded by mirroring the points across the four sides of the box:
    the mirrored cells then share exactly the box's sides with the original ones.
    """
    lo, hi = box.lower, box.upper
    mirrors = [points]
    for axis in (0, 1):
        for edge in (lo[axis], hi[axis]):
            m = points.copy()
            m[:, axis] = 2.0 * edge - m[:, axis]
            mirrors.append(m)
    vor = Voronoi(np.vstack(mirrors))
    cells = []
    for i in range(len(points)):
        region = vor.regions[vor.point_region[i]]
        poly = np.clip(vor.vertices[region], lo, hi)  # clip only rounding noise
        cells.append(poly)
    return cells


def run_voo(n: int) -> VOO:
    opt = make_optimizer("voo", BOX, seed=SEED, omega=OMEGA)
    assert isinstance(opt, VOO)
    f = make_shekel(A, C, BOX, name="shekel2d")
    for _ in range(n):
        x = opt.ask()
        opt.tell(x, f(x))
    return opt


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="docs/figures/voo_voronoi_shekel2d.png")
    args = parser.parse_args()

    f = make_shekel(A, C, BOX, name="shekel2d")
    grid = np.linspace(0.0, 1.0, 301)
    gx, gy = np.meshgrid(grid, grid)
    z = f(np.column_stack([gx.ravel(), gy.ravel()])).reshape(gx.shape)

    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11.5, 5.2), constrained_layout=True)

    # --- left: the function and VOO's samples ------------------------------------------------
    opt = run_voo(N_EVALS)
    xs = opt.xs
    levels = np.geomspace(z.min(), z.max(), 30)
    cf = ax1.contourf(gx, gy, z, levels=levels, norm=LogNorm(), cmap="viridis")
    fig.colorbar(cf, ax=ax1, label="f (log scale)", shrink=0.85, format="%.3g")
    sc = ax1.scatter(
        xs[:, 0], xs[:, 1], c=np.arange(len(xs)), cmap="autumn", s=22, edgecolors="black", lw=0.5
    )
    ax1.scatter(*opt.best_x, marker="*", s=260, c="black", edgecolors="white", zorder=5)
    fig.colorbar(sc, ax=ax1, label="evaluation order", shrink=0.85, location="left")
    ax1.set_title(
        f"VOO on a 2-D Shekel: {N_EVALS} evaluations (omega = {OMEGA}), star = best\n"
        f"best value {opt.best_value:.1f}, optimum {f.optimum_value:.1f}",
        fontsize=10,
    )

    # --- right: the implicit partition and best-cell sampling -------------------------------
    part = run_voo(N_CELLS)
    pts, vals = part.xs, part.values
    best = part.best_index
    cells = voronoi_cells(pts, BOX)
    norm = plt.Normalize(vals.min(), vals.max())
    for i, poly in enumerate(cells):
        face = "gold" if i == best else plt.get_cmap("Greys")(0.15 + 0.5 * norm(vals[i]))
        ax2.add_patch(
            Polygon(poly, closed=True, facecolor=face, edgecolor="black", lw=0.8, alpha=0.9)
        )
    ax2.scatter(pts[:, 0], pts[:, 1], c="white", edgecolors="black", s=40, zorder=4)
    ax2.scatter(*pts[best], c="black", s=70, zorder=5)
    for i, p in enumerate(pts):
        ax2.annotate(str(i + 1), p, textcoords="offset points", xytext=(4, 3), fontsize=7)

    # centered_uniform: try k = 1, 2, ... in the box shrunk towards x* by e^-k.
    rng = np.random.default_rng(1)
    xb = pts[best]
    for k in range(1, 8):
        s = np.exp(-k)
        lo_k, hi_k = xb + (BOX.lower - xb) * s, xb + (BOX.upper - xb) * s
        ax2.add_patch(
            Rectangle(tuple(lo_k), *(hi_k - lo_k), fill=False, ls="--", lw=0.8, ec="tab:blue")
        )
        prop = lo_k + rng.random(2) * (hi_k - lo_k)
        inside = bool(part.in_best_cell(prop[None, :])[0])
        ax2.scatter(
            *prop,
            marker="o" if inside else "x",
            c="tab:green" if inside else "tab:red",
            s=60,
            zorder=6,
        )
        if inside:
            break
    handles = [
        Patch(facecolor="gold", edgecolor="black", label="best cell C(x*)"),
        Line2D([], [], ls="--", c="tab:blue", label="box shrunk by e^-k, k = 1, 2, ..."),
        Line2D([], [], ls="", marker="x", c="tab:red", label="proposal rejected"),
        Line2D([], [], ls="", marker="o", c="tab:green", label=f"proposal accepted (k = {k})"),
    ]
    ax2.legend(handles=handles, loc="upper right", fontsize=8, framealpha=0.9)
    ax2.set_title(
        f"The implicit Voronoi partition after {N_CELLS} evaluations\n"
        "and one draw from the best cell (centered_uniform)",
        fontsize=10,
    )
    for ax in (ax1, ax2):
        ax.set_xlim(0, 1)
        ax.set_ylim(0, 1)
        ax.set_aspect("equal")
        ax.set_xlabel("x1")
        ax.set_ylabel("x2")

    out = Path(args.out)
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=100, metadata={"Software": None})
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
