#!/usr/bin/python3
"""Draws the benchmark CSVs of scripts/benchmark as PNGs: error against the
refined parameter (with the rate of the last two points in the legend) and
error against wall time (work-precision diagrams), with the implicit
boundary method and Nitsche's method on the same axes.

Usage: plot_benchmarks.py CSV_DIRECTORY FIGURE_DIRECTORY
(Debian's python3-matplotlib.)
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(directory, name):
    path = os.path.join(directory, name + ".csv")
    if not os.path.exists(path):
        return None
    with open(path) as f:
        return [{k: float(v) for k, v in row.items()} for row in csv.DictReader(f)]


def rate(rows, key):
    a, b = rows[-2], rows[-1]
    if a[key] <= 0 or b[key] <= 0:
        return float("nan")
    return math.log(a[key] / b[key]) / abs(math.log(a["value"] / b["value"]))


def convergence(directory, figures, name, keys, xlabel, title, out):
    rows = read(directory, name)
    if not rows:
        return
    fig, ax = plt.subplots(figsize=(5.5, 4))
    for key in keys:
        ax.loglog([r["value"] for r in rows], [r[key] for r in rows], "o-",
                  label=f"{key} (rate {rate(rows, key):.2f})")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("error")
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(figures, out), dpi=120)
    plt.close(fig)


def work_precision(directory, figures, series, key, title, out):
    fig, ax = plt.subplots(figsize=(5.5, 4))
    drawn = False
    for name, label in series:
        rows = read(directory, name)
        if not rows:
            continue
        ax.loglog([r["time"] for r in rows], [r[key] for r in rows], "o-", label=label)
        drawn = True
    if not drawn:
        plt.close(fig)
        return
    ax.set_xlabel("wall time of the run (s), best of 3")
    ax.set_ylabel(key)
    ax.set_title(title)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(os.path.join(figures, out), dpi=120)
    plt.close(fig)


def main():
    directory, figures = sys.argv[1], sys.argv[2]
    os.makedirs(figures, exist_ok=True)
    convergence(directory, figures, "column_h", ["L2_u", "L2_sigma"], "cell size h (m)",
                "Column under self weight", "column_h.png")
    convergence(directory, figures, "square_ibm_points", ["R_sigma_yy", "A_v"],
                "points per cell and direction", "1b: square, IBM rollers (Fig. 6)",
                "square_ibm_points.png")
    convergence(directory, figures, "square_ibm_delta", ["R_sigma_yy", "A_u", "A_v"],
                "band width delta / h", "1b: band width, 32^2 points (Fig. 7)",
                "square_ibm_delta.png")
    for form in ("consistent", "frame", "paper"):
        convergence(directory, figures, f"square45_delta_{form}", ["R_v", "R_sigma_yy"],
                    "band width delta / h", f"1c, 45 degrees, {form} form (Fig. 9)",
                    f"square45_delta_{form}.png")
    convergence(directory, figures, "cylinder_h", ["inner_radius_error", "outer_radius_error"],
                "cell size h (m)", "3: thick cylinder, 256^2 points (Fig. 15d)",
                "cylinder_h.png")
    convergence(directory, figures, "plate_neumann_h",
                ["A_u", "A_v", "R_sigma_xx", "L2_sigma"], "cell size h (m)",
                "4a: plate with a hole, Kirsch traction (Fig. 17)", "plate_neumann_h.png")
    convergence(directory, figures, "plate_neumann_h_paper",
                ["A_u", "A_v", "max_A_u", "L2_sigma"], "cell size h (m)",
                "4a by the paper's method (plain quadrature)",
                "plate_neumann_h_paper.png")
    convergence(directory, figures, "plate_dirichlet_h",
                ["A_u", "A_v", "max_A_u", "R_sigma_xx"], "cell size h (m)",
                "4b: plate, Kirsch displacement by IBM (Figs. 20, 21)",
                "plate_dirichlet_h.png")
    work_precision(directory, figures,
                   [("plate_neumann_h", "4a, IBM rollers"),
                    ("plate_neumann_h_paper", "4a, the paper's method"),
                    ("plate_neumann_nitsche_h", "4a, Nitsche rollers"),
                    ("plate_dirichlet_h", "4b, IBM"),
                    ("plate_dirichlet_nitsche_h", "4b, Nitsche"),
                    ("fem_plate_q1", "4a by fitted FEM, Q1"),
                    ("fem_plate_q2", "4a by fitted FEM, Q2")],
                   "L2_u", "Plate with a hole: error against run time",
                   "plate_work_precision.png")
    work_precision(directory, figures,
                   [("plate_neumann_h", "4a, IBM rollers"),
                    ("plate_neumann_nitsche_h", "4a, Nitsche rollers"),
                    ("plate_dirichlet_h", "4b, IBM"),
                    ("plate_dirichlet_nitsche_h", "4b, Nitsche")],
                   "L2_sigma", "Plate with a hole: stress error against run time",
                   "plate_work_precision_stress.png")
    print(f"figures in {figures}")


if __name__ == "__main__":
    main()
