#!/usr/bin/env python3
"""The numbering of bodies does not matter: the strip footing on two layers
(prm/strip-footing-two-layers.prm, a few steps) as a pressure of 40 kPa
(below Prandtl's limit, so that the clay yields under it but holds), with
the top layer von Mises clay and the layer below linear elastic, once with
the clay as the first body and once as Body 2. The largest displacement
and stress must agree to --tolerance in every step: the same points with
the same models, B-bar included for both bodies whichever is first. (A
pressure, because the implicit boundary's band and the contact penalty
take the first body's elastic constants.)
"""
import argparse
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm", required=True,
                    help="prm/strip-footing-two-layers.prm")
parser.add_argument("--np", type=int, default=1)
parser.add_argument("--steps", type=int, default=4)
parser.add_argument("--tolerance", type=float, default=1e-9)
args = parser.parse_args()

top = ["Young's modulus=1e4", "Poisson's ratio=0.3",
       "Constitutive model=von Mises",
       "von Mises/Yield stress=17.320508075688775"]
below = ["Young's modulus=2e4", "Poisson's ratio=0.3",
         "Constitutive model=linear elastic"]
top_region = ["Lower left corner=0, 1.925", "Upper right corner=4, 4.075"]
below_region = ["Lower left corner=0, 1", "Upper right corner=4, 1.925"]


def footing(clay_first):
    first, second = (top, below) if clay_first else (below, top)
    first_region, second_region = (top_region, below_region) if clay_first \
        else (below_region, top_region)
    settings = [f"Loading/Load steps={args.steps}", "Output/Interval=0",
                "Boundary curves/Curve 1/Condition 2=117-160: pressure 40",
                "Reactions/Curves="]
    settings += ["Material/" + s for s in first]
    settings += ["Body 2/Material/" + s for s in second]
    settings += ["Body region/" + s for s in first_region]
    settings += ["Body 2/Body region/" + s for s in second_region]
    summary = run(args.bsmpm, args.prm, args.np, settings)
    return [(s["quantities"]["max_stress"],
             s["quantities"]["max_displacement"]) for s in summary["steps"]]


a, b = footing(True), footing(False)
worst = max(abs(y / x - 1) for p, q in zip(a, b) for x, y in zip(p, q))
print(f"largest displacement {a[-1][1]:.10g} (clay the first body) against "
      f"{b[-1][1]:.10g} (clay Body 2); largest relative difference over "
      f"{len(a)} steps {worst:.2e}")
if len(a) != len(b) or not worst <= args.tolerance:
    print("FAIL: the result depends on the bodies' numbers")
    sys.exit(1)
