#!/usr/bin/env python3
"""Draws the material points of a run with several bodies from a text file
of columns x, y, body, equivalent plastic strain, volume (one row a point;
written from a points-NNNN.pvtu by pvpython, see doc/bodies.md): left the
bodies, right the equivalent plastic strain; with CURVES.txt (columns x,
y from a curves-NNNN.vtu, written the same way) the boundary curves over
both.

Usage: plot_bodies.py POINTS.txt PNG [TITLE [LARGEST PLASTIC STRAIN SHOWN
                                              [CURVES.txt]]]
"""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

data = np.loadtxt(sys.argv[1])
data = data[data[:, 4] > 0]  # material points, not tracking points
x, y, body, plastic = data[:, 0], data[:, 1], data[:, 2], data[:, 3]
figure, axes = plt.subplots(1, 2, figsize=(11, 4.6), sharey=True)
for ax in axes:
    ax.set_aspect("equal")
    ax.set_xlabel("x (m)")
axes[0].set_ylabel("y (m)")
axes[0].scatter(x, y, c=body, s=2, cmap="coolwarm", vmin=0, vmax=1)
axes[0].set_title("body (blue: the first, red: the others)")
cap = float(sys.argv[4]) if len(sys.argv) > 4 else 0.5
shown = axes[1].scatter(x, y, c=np.minimum(plastic, cap), s=2,
                        cmap="viridis")
axes[1].set_title(f"equivalent plastic strain (to {cap:g})")
figure.colorbar(shown, ax=axes[1], shrink=0.8)
if len(sys.argv) > 5:
    curve = np.loadtxt(sys.argv[5])
    for ax in axes:
        ax.plot(curve[:, 0], curve[:, 1], ".", color="black", ms=0.8)
if len(sys.argv) > 3:
    figure.suptitle(sys.argv[3])
figure.tight_layout()
figure.savefig(sys.argv[2], dpi=110)
