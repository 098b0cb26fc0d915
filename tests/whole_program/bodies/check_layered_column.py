#!/usr/bin/env python3
"""Two bonded bodies: the column of prm/layered-column.prm (a soft heavy
top layer over a stiff light one, one-dimensional compression under its own
weight) against its exact settlement at the top,

    u_top = -g [rho1 (H - a)^2 / (2 M1) + (rho1 (H - a) a + rho2 a^2 / 2) / M2],

M = E (1 - nu) / ((1 + nu) (1 - 2 nu)), interface at height a, top H.

1. Interface on a grid line (the scene): the top's settlement (the probe)
   exact to round-off (the bilinear grid holds the exact values at its
   nodes in one-dimensional compression), also with the layers' body
   numbers swapped (the stiff layer the first body).
2. Interface inside a cell (a = 4.25): the settlement within
   --inside-tolerance, the points of each side carrying their own body's
   stiffness and weight.
3. --refine: the interface inside a cell at h = 0.5, 0.25, 0.125; the
   error must fall.
4. The K0 procedure on the two layers: each point starts with the weight of
   the layers above it and its own layer's K0 = nu / (1 - nu); the column
   is then in equilibrium (no displacement), and the largest stress, at
   the lowest row of points (y = h / 4, in the base), is
   |(K0_2 sigma_v, sigma_v)| with sigma_v the weight of both layers above.
"""
import argparse
import pathlib
import sys

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import run  # noqa: E402  (tests/bsmpm_run.py)

parser = argparse.ArgumentParser(description=__doc__)
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--prm", required=True)
parser.add_argument("--np", type=int, default=1)
parser.add_argument("--inside-tolerance", type=float, default=0.01)
parser.add_argument("--refine", action="store_true")
args = parser.parse_args()

g, H = 9.81, 10.0
soft = {"E": 1e7, "nu": 0.3, "rho": 2000.0}   # body 1 in the scene
stiff = {"E": 5e7, "nu": 0.25, "rho": 1800.0}  # Body 2 in the scene


def modulus(m):
    E, nu = m["E"], m["nu"]
    return E * (1 - nu) / ((1 + nu) * (1 - 2 * nu))


def exact_top(a, top, bottom):
    return -g * (top["rho"] * (H - a) ** 2 / (2 * modulus(top))
                 + (top["rho"] * (H - a) * a + bottom["rho"] * a * a / 2)
                 / modulus(bottom))


def material(prefix, m):
    return [f"{prefix}Material/Young's modulus={m['E']}",
            f"{prefix}Material/Poisson's ratio={m['nu']}",
            f"{prefix}Material/Density={m['rho']}"]


def settlement(a, h=0.5, swapped=False):
    """The top's settlement with the interface at height a: the soft layer
    above it, the first body (or Body 2 if swapped)."""
    top_region = [f"Lower left corner=0, {a}", "Upper right corner=1, 10"]
    base_region = ["Lower left corner=0, 0", f"Upper right corner=1, {a}"]
    first, second = (base_region, top_region) if swapped else \
        (top_region, base_region)
    settings = [f"Background grid/Cell size={h}", "Output/Interval=0"]
    settings += [f"Body region/{s}" for s in first]
    settings += [f"Body 2/Body region/{s}" for s in second]
    settings += material("", stiff if swapped else soft)
    settings += material("Body 2/", soft if swapped else stiff)
    summary = run(args.bsmpm, args.prm, args.np, settings)
    return summary["steps"][-1]["quantities"]["top_displacement_y"]


problems = []
for swapped in (False, True):
    u = settlement(4.0, swapped=swapped)
    exact = exact_top(4.0, soft, stiff)
    error = abs(u / exact - 1)
    print(f"interface on a grid line{' (swapped)' if swapped else ''}: "
          f"u_top {u:.12g}, exact {exact:.12g}, relative error {error:.2e}")
    if not error < 1e-10:
        problems.append(f"on a grid line{' (swapped)' if swapped else ''}: "
                        f"relative error {error:.2e}")
for a in (4.25,):
    u = settlement(a)
    exact = exact_top(a, soft, stiff)
    error = abs(u / exact - 1)
    print(f"interface at {a} (inside a cell): u_top {u:.8g}, exact "
          f"{exact:.8g}, relative error {error:.2e}")
    if not error < args.inside_tolerance:
        problems.append(f"interface at {a}: relative error {error:.2e}")
if args.refine:
    errors = []
    for h in (0.5, 0.25, 0.125):
        a = 4.0 + h / 2
        u = settlement(a, h)
        errors.append(abs(u / exact_top(a, soft, stiff) - 1))
        print(f"h = {h}, interface at {a}: relative error {errors[-1]:.2e}")
    if not all(f < c for c, f in zip(errors, errors[1:])):
        problems.append(f"the error does not fall: {errors}")
summary = run(args.bsmpm, args.prm, args.np,
              ["Initial stress/Kind=K0 procedure", "Output/Interval=0"])
q = summary["steps"][-1]["quantities"]
y = 0.5 / 4
sigma_v = g * (soft["rho"] * (H - 4.0) + stiff["rho"] * (4.0 - y))
k0 = stiff["nu"] / (1 - stiff["nu"])
exact = sigma_v * (1 + k0 * k0) ** 0.5
error = abs(q["max_stress"] / exact - 1)
print(f"K0 procedure: largest displacement {q['max_displacement']:.3g}, "
      f"largest stress {q['max_stress']:.10g} against {exact:.10g} "
      f"(relative error {error:.2e})")
if not (q["max_displacement"] < 1e-12 and error < 1e-12):
    problems.append("K0 procedure: not the layers' state at rest")
for p in problems:
    print("FAIL:", p)
sys.exit(1 if problems else 0)
