#!/usr/bin/env python3
"""Load-displacement curve of a support from a bsmpm run's summary.json.

Every load step records the scene's quantities (RunSummary::Step), among
them the force of the supports of curve k (Reactions/Curves = k,
curve<k>_force_x/_y). This script plots the force (or a pressure: force
divided by --width) against the prescribed displacement at each step
(load factor times --displacement) and writes a PNG and a CSV.

Example, the strip footing's load-settlement curve against Prandtl:
  scripts/plot_reaction.py output-strip-footing/summary.json --curve 1 \\
      --component y --displacement 0.1 --width 1.075 --sign -1 \\
      --reference 51.42 --reference-label "Prandtl (2 + pi) c_u" \\
      --xlabel "settlement (m)" --ylabel "bearing pressure (kPa)" \\
      -o footing.png
"""
import argparse
import csv
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("summaries", nargs="+", help="summary.json files (one curve each)")
    parser.add_argument("--curve", type=int, default=1)
    parser.add_argument("--component", choices=["x", "y"], default="y")
    parser.add_argument("--displacement", type=float, default=1.0,
                        help="prescribed displacement at load factor 1 (x axis = load factor times this)")
    parser.add_argument("--width", type=float, default=1.0, help="divide the force by this")
    parser.add_argument("--sign", type=float, default=1.0, help="multiply the force by this")
    parser.add_argument("--reference", type=float, help="horizontal line at this value")
    parser.add_argument("--reference-label", default="reference")
    parser.add_argument("--labels", help="comma-separated legend entries, one per summary")
    parser.add_argument("--xlabel", default="prescribed displacement")
    parser.add_argument("--ylabel", default="support force")
    parser.add_argument("-o", "--output", default="reaction.png")
    args = parser.parse_args()

    key = f"curve{args.curve}_force_{args.component}"
    labels = args.labels.split(",") if args.labels else args.summaries
    fig, ax = plt.subplots(figsize=(6, 4))
    rows = []
    for path, label in zip(args.summaries, labels):
        with open(path) as f:
            summary = json.load(f)
        xs, ys = [0.0], [0.0]
        for step in summary["steps"]:
            quantities = step.get("quantities", {})
            if key not in quantities:
                sys.exit(f"{path}: step {step['step']} has no {key} "
                         f"(set Reactions/Curves = {args.curve})")
            xs.append(step["load_factor"] * args.displacement)
            ys.append(args.sign * quantities[key] / args.width)
            rows.append([label, xs[-1], ys[-1]])
        ax.plot(xs, ys, marker="o", markersize=3, label=label)
    if args.reference is not None:
        ax.axhline(args.reference, color="k", linestyle="--", linewidth=1,
                   label=args.reference_label)
    ax.set_xlabel(args.xlabel)
    ax.set_ylabel(args.ylabel)
    ax.grid(True, linewidth=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.output, dpi=150)
    with open(os.path.splitext(args.output)[0] + ".csv", "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["run", "displacement", "value"])
        writer.writerows(rows)
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
