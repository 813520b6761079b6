"""Draw docs/figures/cutting_frame.png: the cutting frame seen from the spindle, the immersion angle φ,
the clockwise (M3) rotation and the up- and down-milling walls (docs/conventions.md §2).

    python docs/figures/make_cutting_frame.py [OUT.png]
"""
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.patches import Arc, Circle, FancyArrowPatch, Rectangle

R = 1.0   # cutter radius (drawing units)
AE = 0.4  # radial depth of cut a_e


def _arrow(ax, p, q, color="k", **kw):
    ax.add_patch(FancyArrowPatch(p, q, arrowstyle="-|>", mutation_scale=12, color=color, lw=1.4, **kw))


def _panel(ax, mode):
    wall = R - AE
    if mode == "up":
        ax.add_patch(Rectangle((-0.05, wall), 1.9, 1.0, color="0.85", zorder=0))
        ax.plot([-0.05, 1.85], [wall, wall], color="0.4", lw=1)
        ax.text(1.0, wall + 0.5, "material\n(y > R − aₑ)", ha="center", fontsize=8)
        st, ex = 0.0, np.arccos(1 - AE / R)
        title = "up milling: φ ∈ [0, acos(1 − aₑ/R)]"
    else:
        ax.add_patch(Rectangle((-0.05, -wall - 1.0), 1.9, 1.0, color="0.85", zorder=0))
        ax.plot([-0.05, 1.85], [-wall, -wall], color="0.4", lw=1)
        ax.text(1.0, -wall - 0.6, "material\n(y < −(R − aₑ))", ha="center", fontsize=8)
        st, ex = np.pi - np.arccos(1 - AE / R), np.pi
        title = "down milling: φ ∈ [π − acos(1 − aₑ/R), π]"
    ax.add_patch(Circle((0, 0), R, fill=False, lw=1.5))
    # engaged arc: points R(sin φ, cos φ), φ in [st, ex]
    phi = np.linspace(st, ex, 60)
    ax.plot(R * np.sin(phi), R * np.cos(phi), color="tab:red", lw=4, solid_capstyle="butt")
    # axes of the cutting frame
    _arrow(ax, (0, 0), (1.6, 0))
    ax.text(1.62, -0.12, "X (feed)", fontsize=9)
    _arrow(ax, (0, 0), (0, 1.55))
    ax.text(0.05, 1.5, "Y = Z × X", fontsize=9)
    ax.plot(0, 0, "o", ms=7, mfc="white", mec="k")
    ax.plot(0, 0, "o", ms=2, color="k")
    ax.text(-0.42, -0.2, "Z (out of page,\ntip → spindle)", fontsize=7, ha="center")
    # immersion angle of one element
    p = 0.3 * np.pi if mode == "up" else 0.8 * np.pi
    ex_, ey_ = R * np.sin(p), R * np.cos(p)
    ax.plot([0, ex_], [0, ey_], color="tab:blue", lw=1)
    ax.plot(ex_, ey_, "o", color="tab:blue")
    ax.add_patch(Arc((0, 0), 0.7, 0.7, theta1=90 - np.degrees(p), theta2=90, color="tab:blue"))
    mid = p / 2
    ax.text(0.45 * np.sin(mid), 0.45 * np.cos(mid), "φ", color="tab:blue", fontsize=11)
    # clockwise rotation (M3) seen from the spindle
    a0, a1 = np.radians(200), np.radians(120)
    ax.add_patch(FancyArrowPatch((1.2 * R * np.cos(a0), 1.2 * R * np.sin(a0)),
                                 (1.2 * R * np.cos(a1), 1.2 * R * np.sin(a1)),
                                 connectionstyle="arc3,rad=-0.35", arrowstyle="-|>",
                                 mutation_scale=12, color="tab:green", lw=1.4))
    ax.text(-1.55, 0.75, "M3:\nclockwise", color="tab:green", fontsize=8)
    ax.set_title(title, fontsize=9)
    ax.set_xlim(-1.7, 2.2)
    ax.set_ylim(-1.8, 1.8)
    ax.set_aspect("equal")
    ax.axis("off")


def main(out: Path) -> None:
    fig, axes = plt.subplots(1, 2, figsize=(8.4, 4.0))
    _panel(axes[0], "up")
    _panel(axes[1], "down")
    fig.suptitle("Cutting frame seen from the spindle; element at R·(sin φ, cos φ); red: cutting window",
                 fontsize=9)
    fig.tight_layout()
    tmp = out.with_suffix(".tmp.png")
    fig.savefig(tmp, dpi=110)
    tmp.replace(out)
    plt.close(fig)


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(__file__).with_name("cutting_frame.png"))
