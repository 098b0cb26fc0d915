#!/usr/bin/env python3
"""A body cut into two bodies of the same material is the same body: the
plastic strip footing of prm/strip-footing.prm under its own weight
(von Mises clay, density 1.8 t/m^3, the imposed footing pushed down in a
few steps), once as one body and once as two, the top layer the first body
and the rest Body 2, cut along a grid line and inside a row of cells. The
footing's force must agree to --tolerance (round-off: the same points, each
with the same state, summed in another order) in every step, and so must the
largest displacement: with the cut cells integrated by moment fitting (the
curves completed round the rectangle the two bodies fill) and by the points
(Cut cells/Quadrature = plain).
"""
import argparse
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm", required=True, help="prm/strip-footing.prm")
parser.add_argument("--np", type=int, default=1)
parser.add_argument("--steps", type=int, default=6,
                    help="Loading/Load steps (0: the scene's)")
parser.add_argument("--tolerance", type=float, default=1e-9)
parser.add_argument("--width", type=float, default=4.0,
                    help="the body's width (its region from x = 0)")
parser.add_argument("--bottom", type=float, default=1.0,
                    help="the body's lowest y")
parser.add_argument("--cuts", default="3.0,3.1",
                    help="heights of the cut, comma-separated")
parser.add_argument("--quadratures", default="moment fitting,plain",
                    help="Cut cells/Quadrature of the runs, comma-separated")
parser.add_argument("--quantities", default="curve1_force_y,max_displacement",
                    help="the summary's quantities that must agree")
parser.add_argument("--set", action="append", default=[],
                    help="a further setting of both runs (e.g. "
                    "Material/Kinematics=finite strain)")
args = parser.parse_args()

common = ["Output/Interval=0", "Loading/Gravity=0, -9.81",
          "Material/Density=1.8"]
if args.steps > 0:
    common.append(f"Loading/Load steps={args.steps}")
clay = ["Young's modulus=1e4", "Poisson's ratio=0.3",
        "Constitutive model=von Mises",
        "von Mises/Yield stress=17.320508075688775",
        "von Mises/Hardening modulus=0", "Density=1.8"]


def quantities(cut, quadrature):
    settings = common + args.set + [f"Cut cells/Quadrature={quadrature}"]
    if cut is not None:
        settings += [f"Body region/Lower left corner=0, {cut}",
                     "Body 2/Name=lower clay",
                     f"Body 2/Body region/Lower left corner=0, {args.bottom}",
                     f"Body 2/Body region/Upper right corner={args.width}, "
                     f"{cut}",
                     "Body 2/Material points/Points per cell=2"]
        settings += ["Body 2/Material/" + c for c in clay]
    summary = run(args.bsmpm, args.prm, args.np, settings)
    names = args.quantities.split(",")
    return [[s["quantities"][n] for n in names] for s in summary["steps"]]


problems = []
for quadrature in args.quadratures.split(","):
    one = quantities(None, quadrature)
    for cut in (float(c) for c in args.cuts.split(",")):
        two = quantities(cut, quadrature)
        worst = max(abs(b / a - 1) if a != 0 else abs(b)
                    for x, y in zip(one, two) for a, b in zip(x, y))
        print(f"{quadrature}, cut at y = {cut}: {args.quantities} "
              f"{' '.join(f'{v:.10g}' for v in two[-1])} against "
              f"{' '.join(f'{v:.10g}' for v in one[-1])} for one body; "
              f"largest relative difference over {len(two)} steps "
              f"{worst:.2e}")
        if len(two) != len(one) or not worst <= args.tolerance:
            problems.append(f"{quadrature}, cut at y = {cut}: difference "
                            f"{worst:.2e}")
for p in problems:
    print("FAIL:", p)
sys.exit(1 if problems else 0)
