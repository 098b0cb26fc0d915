#!/usr/bin/python3
"""Plots of the stress suite (scripts/stress-suite): error and condition
estimate against the band width and against the fill fraction of cut cells.

Usage: plot_stability.py CSV_DIRECTORY FIGURE_DIRECTORY
"""
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(directory, name):
    path = os.path.join(directory, name + ".csv")
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return list(csv.DictReader(f))


def number(row, key):
    try:
        return float(row[key])
    except (KeyError, ValueError):
        return float("nan")


def panel(ax, rows, x, keys, xlabel, label_suffix=""):
    for key in keys:
        ok = [r for r in rows if r["status"] == "ok"]
        ax.loglog([x(r) for r in ok], [number(r, key) for r in ok], "o-",
                  label=key + label_suffix)
    ax.set_xlabel(xlabel)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)


def main():
    directory, figures = sys.argv[1], sys.argv[2]
    os.makedirs(figures, exist_ok=True)

    fig, axes = plt.subplots(1, 3, figsize=(13, 4))
    for ax, (name, keys, title) in zip(axes, [
            ("delta_1b", ["R_sigma_yy", "A_u", "condition_estimate"], "1b, 8^2 points per cell"),
            ("delta_1c", ["R_v", "R_sigma_yy", "condition_estimate"], "1c, 45 degrees"),
            ("delta_4b", ["A_u", "L2_sigma", "condition_estimate"], "4b, h = 1/8")]):
        rows = read(directory, name)
        panel(ax, rows, lambda r: float(r["value"]), keys, "band width delta / h")
        ax.invert_xaxis()
        ax.set_title(title)
    fig.tight_layout()
    fig.savefig(os.path.join(figures, "stability_delta.png"), dpi=110)
    plt.close(fig)

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, keys in zip(axes, (["R_v", "R_sigma_yy"], ["condition_estimate"])):
        for name, suffix in (("fill_plain", ", no stabilisation"), ("fill_ghost", ", default ghost penalty")):
            rows = read(directory, name)
            fill = lambda r: (float(r["value"].split(",")[1]) - 1) / 0.25
            panel(ax, rows, fill, keys, "fill fraction of the cut cells", suffix)
        ax.invert_xaxis()
    axes[0].set_title("errors (runs that failed are missing)")
    axes[1].set_title("condition estimate")
    fig.tight_layout()
    fig.savefig(os.path.join(figures, "stability_fill.png"), dpi=110)
    plt.close(fig)
    print(f"figures in {figures}")


if __name__ == "__main__":
    main()
