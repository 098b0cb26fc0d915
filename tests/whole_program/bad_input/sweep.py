#!/usr/bin/env python3
"""Bad-input sweep: runs bsmpm on many bad or extreme inputs, each at
np = 1 and np = 2, under a timeout, and judges every run.

At np = 2 a case runs when its run at np = 1 reached the set-up (it
succeeded, or its output directory was made: Scene::setup() makes it after
the input checks), when its class reads files on one process and sends
them (resume, output), and for the first case of every class. The others
stop in the input stage (command line, parameter files, parse_parameters,
InputChecks), which every process goes through alike on the same input with
no communication, so that at np = 2 both processes end as the one did;
--every-case-at-every-np runs them all (twice the process starts, each
about 0.5 s in Debug, most of it in the dynamic linker).

A run is good when it ends by itself within the timeout and either
  - fails cleanly: exit code 1 and a message "bsmpm: error: ..." on stderr
    containing the case's own text, or
  - succeeds: exit code 0 and finite results: summary.json parses, holds no
    NaN, inf or null number, and the output directory holds no temporary
    (*.tmp) or half-written file (every .pvd names files that exist, every
    VTK file is closed by </VTKFile>).
Never a signal, a hang, an abort (deal.II assertion, MPI_Abort), an exit code
other than 0 or 1, or a rank left waiting. Each case states which of the two
outcomes it expects, and the other one is a bad verdict too (a case whose
outcome depends on round-off, CG at its tolerance, accepts either).

Prints a table of cases and verdicts and exits 1 on any bad verdict.

Usage: sweep.py --bsmpm B --source-dir S [--mpirun M] [--np 1,2]
                [--timeout T] [--jobs J] [--only SUBSTRING] [--shard K/N]
                [--list] [--messages] [--keep]
(S is the repository: its prm/ scenes are the cases' starting points.)
"""
import argparse
import concurrent.futures
import json
import math
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2]))
from bsmpm_run import command, kill_session, run as run_bsmpm  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--source-dir", required=True)
parser.add_argument("--mpirun", default="mpirun")
parser.add_argument("--np", default="1,2",
                    help="comma-separated numbers of processes")
parser.add_argument("--timeout", type=float, default=10.,
                    help="seconds a run may take before it counts as a hang")
parser.add_argument("--jobs", type=int, default=2,
                    help="runs at the same time")
parser.add_argument("--only", default="",
                    help="run only the cases whose name contains this")
parser.add_argument("--shard", default="1/1",
                    help="K/N: run only every N-th case, starting with the "
                         "K-th (ctest runs the N shards as N tests, so that "
                         "they spread over its slots)")
parser.add_argument("--every-case-at-every-np", action="store_true",
                    help="run the cases that stop in the input stage at "
                         "every number of processes too")
parser.add_argument("--list", action="store_true",
                    help="list the cases and exit")
parser.add_argument("--messages", action="store_true",
                    help="print each run's error message in the table")
parser.add_argument("--keep", action="store_true",
                    help="keep the working directories (printed)")
args = parser.parse_args()

PRM = os.path.join(os.path.abspath(args.source_dir), "prm")
COLUMN = os.path.join(PRM, "column-self-weight.prm")
SQUARE = os.path.join(PRM, "square-compression.prm")
SQUARE45 = os.path.join(PRM, "square-compression-45.prm")
CYLINDER = os.path.join(PRM, "thick-cylinder.prm")
PLATE = os.path.join(PRM, "plate-with-hole-neumann.prm")
CANTILEVER = os.path.join(PRM, "cantilever.prm")
CANTILEVER_FINITE = os.path.join(PRM, "cantilever-finite-strain.prm")
FOOTING = os.path.join(PRM, "strip-footing.prm")
BLOCK = os.path.join(os.path.abspath(args.source_dir), "tests", "whole_program",
                     "contact", "block_on_plane.prm")

# Every run of a scene: output into the case's own directory, no ParaView
# files (unless a case asks for them), no timing table.
OUTPUT = ["--set", "Output/Interval=0", "--set", "Output/Timing summary=false",
          "--set", "Output/Directory={tmp}/out"]

# Small versions of the scenes (each run takes a fraction of a second).
COLUMN_SMALL = [COLUMN, "--set", "Background grid/Cell size=1"]
SQUARE_SMALL = [SQUARE]
SQUARE45_SMALL = [SQUARE45]
CYLINDER_SMALL = [CYLINDER, "--set", "Material points/Polar points=8, 8",
                  "--set", "Boundary curves/Curve 1/Number of points=9",
                  "--set", "Boundary curves/Curve 2/Number of points=9"]
PLATE_SMALL = [PLATE, "--set", "Background grid/Cell size=0.5",
               "--set", "Material points/Points per cell=2"]


def s(assignment):
    """--set as a list of arguments."""
    return ["--set", assignment]


def curve2(coordinates, closed=False, condition=None):
    """Curve 2 of the square through given coordinates."""
    result = SQUARE_SMALL + s("Boundary curves/Curve 2/Points=coordinates") + \
        s("Boundary curves/Curve 2/Coordinates=" + coordinates)
    if closed:
        result += s("Boundary curves/Curve 2/Closed=true")
    if condition:
        result += s("Boundary curves/Curve 2/Condition=" + condition)
    return result


def write(path, content, mode="w"):
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, mode) as f:
        f.write(content)


def binary_bytes():
    """Bytes of every value (NUL, control characters, invalid UTF-8)."""
    return bytes((i * 37 + 11) % 256 for i in range(4096))


# Files the cases use, made in each run's working directory.
def make_files(tmp):
    write(os.path.join(tmp, "empty.prm"), "")
    write(os.path.join(tmp, "binary.prm"), binary_bytes(), "wb")
    write(os.path.join(tmp, "self.prm"), "include self.prm\n")
    write(os.path.join(tmp, "a.prm"), "include b.prm\n")
    write(os.path.join(tmp, "b.prm"), "include a.prm\n")
    write(os.path.join(tmp, "include-missing.prm"),
          "include " + COLUMN + "\ninclude nowhere.prm\n")
    os.makedirs(os.path.join(tmp, "a-directory"), exist_ok=True)
    write(os.path.join(tmp, "include-directory.prm"),
          "include " + COLUMN + "\ninclude a-directory\n")
    with open(COLUMN) as f:
        column = f.read()
    write(os.path.join(tmp, "crlf.prm"),
          column.replace("\n", "\r\n").replace(
              "set Cell size          = 0.5", "set Cell size = 1"))
    write(os.path.join(tmp, "unbalanced.prm"),
          "include " + COLUMN + "\nsubsection Material\n"
          "  set Young's modulus = 1e7\n")
    write(os.path.join(tmp, "extra-end.prm"),
          "include " + COLUMN + "\nend\n")
    write(os.path.join(tmp, "empty.csv"), "")
    write(os.path.join(tmp, "binary.csv"), binary_bytes(), "wb")
    write(os.path.join(tmp, "nan.csv"), "x, y\n0.2, 0.2\nnan, 0.5\n0.8, 0.6\n")
    write(os.path.join(tmp, "a-file"), "not a directory\n")
    # Checkpoints that are not: empty files, garbage, a bare directory.
    for name in ("state", "points", "parameters.prm"):
        write(os.path.join(tmp, "empty-checkpoint", "checkpoint-1", name), "")
        write(os.path.join(tmp, "garbage-checkpoint", "checkpoint-3", name),
              binary_bytes(), "wb")
    for name in ("state", "points", "triangulation", "triangulation.info",
                 "triangulation_fixed.data"):
        write(os.path.join(tmp, "garbage-with-parameters", "checkpoint-2",
                           name), binary_bytes(), "wb")
    shutil.copy(COLUMN, os.path.join(tmp, "garbage-with-parameters",
                                     "checkpoint-2", "parameters.prm"))
    os.makedirs(os.path.join(tmp, "bare-checkpoint", "checkpoint-5"),
                exist_ok=True)


def checkpointed_run(tmp, damage):
    """A column run of 3 steps with checkpoints into tmp/ck, then
    damage(tmp/ck/checkpoint-2)."""
    run_bsmpm(args.bsmpm, COLUMN, settings=[
        "Background grid/Cell size=1", "Loading/Load steps=3",
        "Output/Interval=0", "Output/Checkpoint interval=1"],
        directory=f"{tmp}/ck", cwd=tmp, timeout=args.timeout)
    damage(os.path.join(tmp, "ck", "checkpoint-2"))


def truncate(path):
    """Cuts a file to half its length."""
    size = os.path.getsize(path)
    with open(path, "r+b") as f:
        f.truncate(size // 2)


class Either(str):
    """Expectation of a case whose outcome is not determined: success, or
    an error whose message contains this text."""


class Case:
    def __init__(self, name, kind, arguments, expect, prepare=None):
        self.name = name
        self.kind = kind        # the parameter class, for the table
        self.arguments = arguments
        # OK, the text the error message must contain, or Either(text)
        self.expect = expect
        # prepare(tmp): makes what the case needs beyond make_files()
        self.prepare = prepare


CASES = []


def case(name, kind, arguments, expect, prepare=None):
    CASES.append(Case(name, kind, arguments, expect, prepare))


OK = "ok"


def expectation(case):
    if case.expect == OK:
        return "succeeds"
    if isinstance(case.expect, Either):
        return "succeeds or error: " + case.expect
    return "error: " + case.expect

# --- negative values -------------------------------------------------------
case("negative_youngs_modulus", "negative",
     COLUMN_SMALL + s("Material/Young's modulus=-1e7"),
     "Young's modulus must be positive")
case("negative_load_steps", "negative",
     COLUMN_SMALL + s("Loading/Load steps=-3"), "Load steps")
case("negative_radius", "negative",
     CYLINDER_SMALL + s("Body region/Inner radius=-1"), "Inner radius")
case("negative_pressure_is_tension", "negative",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Condition=pressure -8000") +
     s("Background grid/Upper right corner=1, 1.5") +
     s("Background grid/Cells per direction=2, 3") +
     s("Verification/Bounds="), OK)
case("poissons_ratio_near_minus_one", "negative",
     COLUMN_SMALL + s("Material/Poisson's ratio=-0.999") +
     s("Exact solution/Name=none"), OK)

# --- zero ------------------------------------------------------------------
case("zero_youngs_modulus", "zero",
     COLUMN_SMALL + s("Material/Young's modulus=0"),
     "Young's modulus must be positive")
case("zero_load_steps", "zero",
     COLUMN_SMALL + s("Loading/Load steps=0"), "Load steps")
case("zero_gravity", "zero",
     COLUMN_SMALL + s("Loading/Gravity=0, 0"), OK)
case("zero_width", "zero",
     SQUARE45_SMALL + s("Body region/Width=0"),
     "width and height of a rotated rectangle must be positive")
case("zero_solver_tolerance", "zero",
     COLUMN_SMALL + s("Linear solver/Method=cg amg") +
     s("Linear solver/Tolerance=0"), "Tolerance")
case("zero_disc_radius", "zero",
     PLATE_SMALL + s("Body region/Disc radius=0"),
     "Disc radius of a rectangle minus disc must be positive")
case("zero_height_column", "zero",
     COLUMN_SMALL + s("Exact solution/Column/Height=0"),
     "the column height must be positive")

# --- huge ------------------------------------------------------------------
case("huge_youngs_modulus", "huge",
     COLUMN_SMALL + s("Material/Young's modulus=1e300"), OK)
case("huge_density", "huge",
     COLUMN_SMALL + s("Material/Density=1e30"), "far too large")
case("huge_pressure", "huge",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Condition=pressure 1e20"),
     "far too large")
case("huge_load_steps", "huge",
     COLUMN_SMALL + s("Loading/Load steps=1000000000"), "Load steps")
case("huge_iterations_tiny_tolerance", "huge",
     SQUARE45_SMALL + s("Linear solver/Method=cg amg") +
     s("Linear solver/Tolerance=1e-300") +
     s("Linear solver/Maximum iterations=2000000000"), "Tolerance")
case("huge_iterations_small_tolerance", "huge",
     SQUARE45_SMALL + s("Linear solver/Method=cg amg") +
     s("Linear solver/Tolerance=1e-15") +
     s("Linear solver/Maximum iterations=2000000000"),
     Either("did not converge"))
case("many_load_steps", "huge",
     COLUMN_SMALL + s("Loading/Load steps=12"), OK)
case("huge_cells_per_direction", "huge",
     COLUMN_SMALL + s("Background grid/Cell size=0") +
     s("Background grid/Cells per direction=100000, 100000"), "2e9 cells")
case("tiny_cell_size", "huge",
     COLUMN_SMALL + s("Background grid/Cell size=1e-5"), "2e9 cells")
case("absurd_cell_size", "huge",
     COLUMN_SMALL + s("Background grid/Cell size=1e-12"), "Background grid")
case("huge_grid_coordinates", "huge",
     COLUMN_SMALL + s("Background grid/Upper right corner=1e300, 1e300"),
     "Background grid")
case("grid_side_overflow", "huge",
     COLUMN_SMALL + s("Background grid/Lower left corner=-1e308, 0") +
     s("Background grid/Upper right corner=1e308, 10"),
     "the side of the grid in direction 0: the value is not a finite number")
case("huge_points_per_cell", "huge",
     COLUMN_SMALL + s("Material points/Points per cell=100000"), "memory")
case("huge_gauss_points", "huge",
     SQUARE_SMALL + s("Boundary curves/Gauss points per piece=1000000000"),
     "Gauss points per piece")
case("huge_points_on_edge", "huge",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Number of points=2000000000"),
     "Number of points")
case("huge_band_points", "huge",
     SQUARE45_SMALL + s("Implicit boundary/Points along piece=1000000000"),
     "Points along piece")

# --- NaN and inf -----------------------------------------------------------
case("nan_youngs_modulus", "nan/inf",
     COLUMN_SMALL + s("Material/Young's modulus=nan"), "Young's modulus")
case("inf_gravity", "nan/inf",
     COLUMN_SMALL + s("Loading/Gravity=0, -inf"), "Gravity")
case("nan_coordinates", "nan/inf",
     curve2("0.2, 0.2; 0.5, nan; 0.8, 0.6"), "Coordinates")
case("inf_pressure", "nan/inf",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Condition=pressure inf"),
     "Curve 1/Condition: the value is not a finite number")
case("nan_traction_expression", "nan/inf",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Condition=traction 0; "
                      "sqrt(-1 - y)"), "not a finite vector")
case("division_by_zero_traction", "nan/inf",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Condition=traction x/0; 0"),
     "not a finite vector")
case("nan_in_points_file", "nan/inf",
     SQUARE_SMALL + s("Boundary curves/Curve 2/Points=file") +
     s("Boundary curves/Curve 2/File={tmp}/nan.csv"), "line 3 of")
case("inf_bound", "nan/inf",
     SQUARE_SMALL + s("Verification/Bounds=R_v <= inf"),
     "is not a finite number")

# --- empty values ----------------------------------------------------------
case("empty_youngs_modulus", "empty",
     COLUMN_SMALL + s("Material/Young's modulus="), "Young's modulus")
case("empty_coordinates", "empty", curve2(""), "Curve 2")
case("empty_points_file_name", "empty",
     SQUARE_SMALL + s("Boundary curves/Curve 2/Points=file") +
     s("Boundary curves/Curve 2/File="), "points file")
case("empty_output_directory", "empty",
     COLUMN_SMALL + s("Output/Directory="), "directory")
case("empty_condition", "empty",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Condition=") +
     s("Verification/Bounds="), OK)
case("empty_edge", "empty",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Edge="), "no edge")
case("empty_set", "empty", COLUMN_SMALL + s(""), "Section/Name=value")

# --- malformed values ------------------------------------------------------
case("point_with_semicolon", "malformed",
     COLUMN_SMALL + s("Loading/Gravity=0; -9.81"), "Gravity")
case("misspelt_model", "malformed",
     COLUMN_SMALL + s("Material/Model=plane strian"), "Model")
case("unknown_condition", "malformed",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Condition=pressur 8000"),
     "unknown condition 'pressur 8000'")
case("pressure_not_a_number", "malformed",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Condition=pressure abc"),
     "'pressure' needs a number")
case("broken_expression", "malformed",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Condition=traction x+; 0"),
     "needs two expressions")
case("one_expression", "malformed",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Condition=traction x"),
     "needs two expressions")
case("malformed_range", "malformed",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Condition 2=a-b: free"),
     "is not a range of points")
case("range_beyond_chain", "malformed",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Condition 2=50-60: free"),
     "lies beyond the chain")
# The footing's base is 117-160 on the open chain of the soil surface; its
# reverse used to be taken as the range that wraps round a closed chain (the
# rest of the surface), and ran.
case("range_reversed_on_open_chain", "malformed",
     [FOOTING] + s("Loading/Load steps=1") +
     s("Boundary curves/Curve 1/Condition 2=160-117: displacement 0; -0.1"),
     "Boundary curves/Curve 1/Condition 2: the range '160-117' runs "
     "backwards: Curve 1 is an open chain of 161 points, numbered from 0 to "
     "160")
case("range_equal_endpoints", "malformed",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Condition 2=2-2: fixed"),
     "Curve 1/Condition 2: the range '2-2' starts and ends at point 2, so it "
     "covers no segment")
case("range_negative_index", "malformed",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Condition 2=1--1: free"),
     "Curve 1/Condition 2: '1--1' is not a range of points 'i-j': point "
     "indices count from 0")
# Point 4 of a closed chain of 4 points is point 0 again: as an end it is
# 'after a full turn', as a start it is refused.
case("range_beyond_closed_chain", "malformed",
     curve2("0.3, 0.3; 0.7, 0.3; 0.7, 0.7; 0.3, 0.7", closed=True) +
     s("Boundary curves/Curve 2/Condition 2=4-2: free"),
     "Curve 2/Condition 2: the range '4-2' lies beyond the chain: Curve 2 is "
     "a closed chain of 4 points")
case("range_wrapping_closed_chain", "malformed",
     curve2("0.3, 0.3; 0.7, 0.3; 0.7, 0.7; 0.3, 0.7", closed=True) +
     s("Boundary curves/Curve 2/Condition 2=3-1: free"), OK)
case("malformed_bound", "malformed",
     SQUARE_SMALL + s("Verification/Bounds=R_v < 1"), "must read")
case("malformed_coordinates", "malformed",
     curve2("0.2 0.2; 0.8"), "is not a point")
case("malformed_lattice_corner", "malformed",
     COLUMN_SMALL + s("Material points/Layout=lattice") +
     s("Material points/Lattice lower left corner=abc"),
     "Lattice lower left corner")
case("exact_traction_without_solution", "malformed",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Condition=exact traction") +
     s("Exact solution/Name=none") + s("Verification/Bounds="),
     "needs an exact solution")
case("displacement_exact_without_solution", "malformed",
     SQUARE45_SMALL + s("Boundary curves/Curve 2/Condition=displacement exact")
     + s("Exact solution/Name=none"), "needs an exact solution")
case("polar_layout_on_rectangle", "malformed",
     COLUMN_SMALL + s("Material points/Layout=polar"),
     "polar layout needs an annulus sector")

# --- files -----------------------------------------------------------------
case("missing_parameter_file", "file", ["{tmp}/nowhere.prm"],
     "cannot read the parameter file")
case("empty_parameter_file", "file", ["{tmp}/empty.prm"], "no support")
case("binary_parameter_file", "file", ["{tmp}/binary.prm"],
     "binary.prm' is not a parameter file")
case("self_including_file", "file", ["{tmp}/self.prm"], "a cycle")
case("mutually_including_files", "file", ["{tmp}/a.prm"], "a cycle")
case("include_missing_file", "file", ["{tmp}/include-missing.prm"],
     "nowhere.prm")
case("include_directory", "file", ["{tmp}/include-directory.prm"],
     "a-directory' (included by line 2 of")
case("parameter_file_is_directory", "file", ["{tmp}/a-directory"],
     "a-directory': it is a directory")
case("crlf_line_ends", "file", ["{tmp}/crlf.prm"], OK)
case("unbalanced_subsection", "file", ["{tmp}/unbalanced.prm"],
     "unbalanced.prm' (with the files it includes)")
case("extra_end", "file", ["{tmp}/extra-end.prm"], "end")
case("points_file_missing", "file",
     SQUARE_SMALL + s("Boundary curves/Curve 2/Points=file") +
     s("Boundary curves/Curve 2/File={tmp}/nowhere.csv"),
     "cannot read the points file")
case("points_file_empty", "file",
     SQUARE_SMALL + s("Boundary curves/Curve 2/Points=file") +
     s("Boundary curves/Curve 2/File={tmp}/empty.csv"), "Curve 2")
case("points_file_binary", "file",
     SQUARE_SMALL + s("Boundary curves/Curve 2/Points=file") +
     s("Boundary curves/Curve 2/File={tmp}/binary.csv"), "is not a point")
case("points_file_is_directory", "file",
     SQUARE_SMALL + s("Boundary curves/Curve 2/Points=file") +
     s("Boundary curves/Curve 2/File={tmp}/a-directory"),
     "a-directory' is not a regular file")

# --- output directory ------------------------------------------------------
case("output_directory_unwritable", "output",
     COLUMN_SMALL + s("Output/Directory=/proc/bsmpm-sweep"),
     "cannot use the output directory")
case("output_directory_is_file", "output",
     COLUMN_SMALL + s("Output/Directory={tmp}/a-file"),
     "cannot use the output directory")
case("output_directory_below_file", "output",
     COLUMN_SMALL + s("Output/Directory={tmp}/a-file/out"),
     "cannot use the output directory")
case("output_every_step", "output",
     COLUMN_SMALL + s("Loading/Load steps=3") + s("Output/Interval=1") +
     s("Output/Checkpoint interval=1"), OK)

# --- grids -----------------------------------------------------------------
case("grid_smaller_than_body", "grid",
     COLUMN_SMALL + s("Background grid/Upper right corner=1, 5"),
     "outside the background grid")
case("grid_inverted", "grid",
     COLUMN_SMALL + s("Background grid/Upper right corner=-1, 10"),
     "upper right corner must lie above and to the right")
case("grid_one_cell", "grid",
     SQUARE_SMALL + s("Background grid/Cells per direction=1, 1"), OK)
case("cell_size_not_dividing", "grid",
     COLUMN_SMALL + s("Background grid/Cell size=0.3"), "does not divide")
case("grid_away_from_body", "grid",
     COLUMN_SMALL + s("Background grid/Lower left corner=5, 0") +
     s("Background grid/Upper right corner=6, 10"),
     "outside the background grid")

# --- curves ----------------------------------------------------------------
case("curve_outside_grid", "curve",
     curve2("0.2, 0.2; 0.5, 1.5; 0.8, 0.6"), "outside the background grid")
case("curve_crossing_itself", "curve",
     curve2("0.2, 0.2; 0.8, 0.8; 0.8, 0.2; 0.2, 0.8", closed=True),
     "intersects itself")
case("open_curve_crossing_itself", "curve",
     curve2("0.3, 0.3; 0.7, 0.7; 0.7, 0.3; 0.3, 0.7"),
     "In the input: Boundary curves/Curve 2 touches itself")
case("spline_overshooting_grid", "curve",
     curve2("0.1, 0.5; 0.9, 0.9; 0.9, 0.1; 0.5, 0.1"),
     "Curve 2: The boundary curve leaves the background grid")
case("curves_crossing_each_other", "curve",
     curve2("0.5, 0.5; 0.5, 1.25", condition="pressure 1000") +
     s("Background grid/Upper right corner=1, 1.5") +
     s("Background grid/Cells per direction=2, 3") +
     s("Verification/Bounds="), "In the input: Boundary curves/Curve 1 touches Curve 2")
case("curve_repeated_point", "curve",
     curve2("0.2, 0.2; 0.5, 0.5; 0.5, 0.5; 0.8, 0.6"), "Curve 2")
case("curve_all_points_equal", "curve",
     curve2("0.5, 0.5; 0.5, 0.5; 0.5, 0.5"), "Curve 2")
case("curve_two_points", "curve", curve2("0.2, 0.2; 0.8, 0.6"), OK)
case("curve_one_point", "curve", curve2("0.2, 0.2"), "Curve 2")
case("curve_near_duplicate_points", "curve",
     curve2("0.2, 0.2; 0.5, 0.5; 0.5, 0.5000000000001; 0.8, 0.6"),
     "Points 1 and 2 of a boundary curve coincide")
case("curve_corner_beyond_chain", "curve",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Corners=99"),
     "corner index 99 lies beyond the chain")
case("curve_unknown_edge", "curve",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Edge=diagonal"),
     "has no edge 'diagonal'")
case("edge_of_sector_on_rectangle", "curve",
     SQUARE_SMALL + s("Boundary curves/Curve 1/Edge=inner arc"),
     "Boundary curves/Curve 1/Edge: the body region (Shape = rectangle) has "
     "no edge 'inner arc'; it has 'bottom', 'right', 'top', 'left' and "
     "'boundary'")
case("edge_of_rectangle_on_sector", "curve",
     CYLINDER_SMALL + s("Boundary curves/Curve 2/Edge=top"),
     "Boundary curves/Curve 2/Edge: the body region (Shape = annulus sector) "
     "has no edge 'top'")

# The D-scaled forms of the implicit boundary method keep the
# small-strain band terms: refused in finite strain. "frame" and "paper" are
# their names of before, still read; the message names the form as it is
# called now.
for name, value, form in (("d_scaled", "D-scaled", "D-scaled"),
                          ("frame", "frame", "D-scaled"),
                          ("paper", "paper", "D-scaled with J_T")):
    case(f"implicit_boundary_{name}_in_finite_strain", "curve",
         [CANTILEVER_FINITE] + s("Loading/Load steps=1") +
         s(f"Implicit boundary/Formulation={value}"),
         f"Implicit boundary/Formulation = {form} keeps the small-strain "
         "band terms")

# Curves of material points with less than one point per cell in a
# direction: along the region's edge (the default) the cut cells are
# integrated exactly and the run completes (in finite strain too: test
# finite_strain/few_points_per_cell);
# through the points with full volumes the cells are integrated by their
# points alone, and the system may be singular: then an error that says so
# (never KLU's displacements of a singular system, or a point thrown off the
# grid).
FEW_POINTS = s("Background grid/Cell size=0.25") + \
    s("Material points/Lattice points=28, 8") + \
    s("Boundary curves/Curve 2/Condition 2=3-4: fixed") + \
    s("Probe/Point=10.071428571428571, 1.5") + s("Loading/Load steps=1")
case("cantilever_less_than_a_point_per_cell", "curve",
     [CANTILEVER] + FEW_POINTS, OK)
case("cantilever_through_the_points_few_points", "curve",
     [CANTILEVER] + FEW_POINTS +
     [a for k in range(1, 5) for a in
      s(f"Boundary curves/Curve {k}/Curve position=through the points")],
     Either("singular"))

# --- angles ----------------------------------------------------------------
# An angle beyond a full turn is refused, not taken modulo 360.
case("rotation_beyond_full_turn", "angle",
     SQUARE45_SMALL + s("Body region/Angle=405"),
     "Body region/Angle: 405 degrees is more than a full turn")
case("sector_start_beyond_full_turn", "angle",
     CYLINDER_SMALL + s("Body region/Start angle=720") +
     s("Body region/End angle=810"),
     "Body region/Start angle: 720 degrees is more than a full turn")
case("sector_angles_reversed", "angle",
     CYLINDER_SMALL + s("Body region/Start angle=90") +
     s("Body region/End angle=0"),
     "start angle < end angle <= start angle + 360 (degrees, "
     "counter-clockwise), got radii 1, 5 and angles 90, 0")
case("stress_frame_beyond_full_turn", "angle",
     SQUARE45_SMALL + s("Exact solution/Constant stress/Angle=405"),
     "Exact solution/Constant stress/Angle: 405 degrees is more than a full "
     "turn")

# --- rigid bodies ----------------------------------------------------------
case("rigid_body_clockwise", "rigid body",
     COLUMN_SMALL + s("Rigid body 1/Shape=polygon") +
     s("Rigid body 1/Vertices=0, 0; 0, 1; 1, 1; 1, 0"),
     "must run counter-clockwise")
case("rigid_body_two_vertices", "rigid body",
     COLUMN_SMALL + s("Rigid body 1/Shape=polygon") +
     s("Rigid body 1/Vertices=0, 0; 1, 0"), "give at least 3 vertices")
case("rigid_body_vertex_not_a_point", "rigid body",
     COLUMN_SMALL + s("Rigid body 1/Shape=polygon") +
     s("Rigid body 1/Vertices=0, 0; 1; 1, 1"), "give at least 3 vertices")
case("rigid_body_zero_radius", "rigid body",
     COLUMN_SMALL + s("Rigid body 1/Shape=circle") +
     s("Rigid body 1/Radius=0"), "Radius must be positive")
case("rigid_body_bad_motion", "rigid body",
     COLUMN_SMALL + s("Rigid body 1/Shape=circle") +
     s("Rigid body 1/Displacement=0; -0.1*s"), "is not two expressions")
case("rigid_body_one_motion_component", "rigid body",
     COLUMN_SMALL + s("Rigid body 1/Shape=circle") +
     s("Rigid body 1/Displacement=-0.1*t"), "is not two expressions")
# pi in a rigid body's motion, as in a curve's condition.
case("rigid_body_motion_with_pi", "rigid body",
     COLUMN_SMALL + s("Rigid body 1/Shape=circle") +
     s("Rigid body 1/Center=0.5, 11") +
     s("Rigid body 1/Displacement=0; -0.1*sin(pi*t/2)"), OK)
case("rigid_body_motion_not_finite", "rigid body",
     COLUMN_SMALL + s("Rigid body 1/Shape=circle") +
     s("Rigid body 1/Displacement=0; 1/(t-0.5)"), "is not finite")
# Where a rigid body starts: inside the column (its top 1 m), overlapping
# another, or pressed into the column's top by a hundredth of a cell (taken
# as touching: up to a twentieth is).
case("rigid_body_inside_body", "rigid body",
     COLUMN_SMALL + s("Rigid body 1/Shape=polygon") +
     s("Rigid body 1/Vertices=0, 9; 1, 9; 1, 11; 0, 11"),
     "Rigid body 1 starts inside the body: the body's material lies up to "
     "0.25 m inside its outline")
case("rigid_bodies_overlapping", "rigid body",
     COLUMN_SMALL + s("Rigid body 1/Shape=circle") +
     s("Rigid body 1/Center=3, 5") + s("Rigid body 2/Shape=circle") +
     s("Rigid body 2/Center=4, 5"),
     "Rigid body 1 and Rigid body 2 overlap by 1 m")
# A block on a frictional plane steeper than its friction angle: the
# failed increment says that only friction holds it (one cut, not six: at
# np = 2 in Debug the six took longer than the timeout).
case("friction_cannot_hold", "rigid body",
     [BLOCK] + s("Loading/Gravity=4.38577, -8.77154") +
     s("Nonlinear solver/Maximum step cuts=1"),
     "a body that only friction holds has no quasi-static equilibrium")
case("rigid_body_pressed_in_slightly", "rigid body",
     COLUMN_SMALL + s("Rigid body 1/Shape=polygon") +
     s("Rigid body 1/Vertices=0, 9.99; 1, 9.99; 1, 11; 0, 11"), OK)

# --- command line ----------------------------------------------------------
case("set_without_argument", "command line", COLUMN_SMALL + ["--set"],
     "--set needs an argument")
case("set_without_equals", "command line",
     COLUMN_SMALL + s("Material/Young's modulus"), "Section/Name=value")
case("set_unknown_section", "command line",
     COLUMN_SMALL + s("Materials/Young's modulus=1"), "Did you mean")
case("set_value_with_newline", "command line",
     COLUMN_SMALL + s("Loading/Load steps=1\nend\nend"),
     "the value must be a single line")
case("sweep_without_values", "command line",
     COLUMN_SMALL + ["--sweep", "Loading/Load steps="], "no values")
case("sweep_bad_value", "command line",
     COLUMN_SMALL + ["--sweep", "Loading/Load steps=1,0"], "Load steps")
case("two_parameter_files", "command line", COLUMN_SMALL + [SQUARE],
     "more than one parameter file")
case("no_parameter_file", "command line", [], "no parameter file given")
case("unknown_option", "command line", COLUMN_SMALL + ["--frobnicate"],
     "unknown option")

# --- resume ----------------------------------------------------------------
case("resume_missing", "resume", ["--resume", "{tmp}/nowhere"],
     "no such directory")
case("resume_empty_checkpoint", "resume",
     ["--resume", "{tmp}/empty-checkpoint"], "checkpoint-1")
case("resume_garbage_checkpoint", "resume",
     ["--resume", "{tmp}/garbage-checkpoint"], "checkpoint-3")
case("resume_garbage_with_parameters", "resume",
     ["--resume", "{tmp}/garbage-with-parameters"], "checkpoint-2")
case("resume_bare_checkpoint", "resume",
     ["--resume", "{tmp}/bare-checkpoint"], "neither a checkpoint")
case("resume_intact", "resume", ["--resume", "{tmp}/ck"], OK,
     prepare=lambda tmp: checkpointed_run(tmp, lambda d: None))
case("resume_truncated_points", "resume", ["--resume", "{tmp}/ck"],
     "checkpoint-2", prepare=lambda tmp: checkpointed_run(
         tmp, lambda d: truncate(os.path.join(d, "points"))))
case("resume_truncated_state", "resume", ["--resume", "{tmp}/ck"],
     "checkpoint-2", prepare=lambda tmp: checkpointed_run(
         tmp, lambda d: truncate(os.path.join(d, "state"))))
case("resume_grid_file_missing", "resume", ["--resume", "{tmp}/ck"],
     "checkpoint-2", prepare=lambda tmp: checkpointed_run(
         tmp, lambda d: os.remove(os.path.join(d, "triangulation_fixed.data"))))
case("resume_bad_parameters", "resume", ["--resume", "{tmp}/ck"],
     "Load steps", prepare=lambda tmp: checkpointed_run(
         tmp, lambda d: write(os.path.join(d, "parameters.prm"),
                              "subsection Loading\n  set Load steps = 0\nend\n",
                              "a")))
case("resume_with_parameter_file", "resume",
     ["--resume", "{tmp}/garbage-checkpoint", COLUMN],
     "--resume takes no parameter file")


# --------------------------------------------------------------------------

def non_finite(value, path="summary"):
    """Paths of the NaN, inf and null numbers in a parsed JSON value."""
    if isinstance(value, dict):
        return [p for k, v in value.items() for p in non_finite(v, f"{path}.{k}")]
    if isinstance(value, list):
        return [p for i, v in enumerate(value)
                for p in non_finite(v, f"{path}[{i}]")]
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return [path]
    return []


def check_output(directory):
    """Problems with a run's output directory: temporary files, files named
    by a collection but missing, VTK files not closed."""
    problems = []
    if not os.path.isdir(directory):
        return problems
    for root, _, files in os.walk(directory):
        for f in files:
            path = os.path.join(root, f)
            if f.endswith(".tmp") or ".tmp" in os.path.relpath(path, directory):
                problems.append(f"temporary file {os.path.relpath(path, directory)}")
            if f.endswith((".vtu", ".pvtu", ".pvd")):
                with open(path, "rb") as h:
                    if b"</VTKFile>" not in h.read()[-200:]:
                        problems.append(f"{f} is not closed")
            if f.endswith(".pvd"):
                with open(path) as h:
                    for part in h.read().split('file="')[1:]:
                        named = part.split('"')[0]
                        if not os.path.exists(os.path.join(root, named)):
                            problems.append(f"{f} names missing {named}")
    return problems


def judge(case, returncode, out, err, directory):
    """'' when the run is good, else what is wrong."""
    text = out + err
    if returncode is None:
        return "hang (timeout)"
    if returncode < 0 or returncode >= 128:
        return f"signal/crash (exit code {returncode})"
    for mark in ("An error occurred in line", "terminate called",
                 "Segmentation fault", "Aborted", "MPI_ABORT",
                 "Assertion", "Stacktrace"):
        if mark in text:
            return f"abort ('{mark}' in the output)"
    if returncode not in (0, 1):
        return f"exit code {returncode}"
    problems = check_output(directory)
    if returncode == 1:
        if case.expect == OK:
            return "failed: " + (err.strip().splitlines() or ["(no message)"])[0][:120]
        if "bsmpm: error:" not in err:
            return "exit code 1 without a 'bsmpm: error:' message on stderr"
        if case.expect not in err:
            return f"message lacks '{case.expect}'"
        return "; ".join(problems)
    # returncode == 0
    if case.expect != OK and not isinstance(case.expect, Either):
        return "succeeded, expected an error"
    summary = os.path.join(directory, "summary.json")
    if not os.path.isfile(summary):
        return "no summary.json"
    try:
        with open(summary) as f:
            data = json.load(f)
    except ValueError as e:
        return f"summary.json does not parse: {e}"
    bad = non_finite(data)
    if bad:
        return "non-finite values: " + ", ".join(bad[:4])
    if not data.get("steps"):
        return "summary.json has no steps"
    return "; ".join(problems)


def run(case, np):
    tmp = tempfile.mkdtemp(prefix=f"sweep-{case.name}-np{np}-")
    make_files(tmp)
    if case.prepare:
        case.prepare(tmp)
    arguments = OUTPUT + case.arguments
    arguments = [a.replace("{tmp}", tmp) for a in arguments]
    # odls_base_sigkill_timeout 0: when a rank ends with exit code 1, mpirun
    # stops the job's other ranks at once with SIGKILL rather than with
    # SIGTERM and a second's grace before SIGKILL, twice (measured:
    # 'mpirun -np 1 false' 2.1 s, with the option 0.15 s). Every error case
    # at np = 2 waited those 2 s. What is judged stays: mpirun's exit code
    # is still that of the first rank to fail, and bsmpm does not catch
    # SIGTERM, so the other ranks ended the same way before, only later.
    line = command(args.bsmpm, np=np, arguments=arguments,
                   mpirun=args.mpirun,
                   mpirun_options=["--mca", "odls_base_sigkill_timeout", "0"])
    start = time.time()
    process = subprocess.Popen(line, cwd=tmp, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, text=True,
                               errors="replace", start_new_session=True)
    try:
        out, err = process.communicate(timeout=args.timeout)
        returncode = process.returncode
    except subprocess.TimeoutExpired:
        kill_session(process)
        out, err = process.communicate()
        returncode = None
    seconds = time.time() - start
    verdict = judge(case, returncode, out, err, os.path.join(tmp, "out"))
    message = ""
    for line in err.splitlines():
        if line.startswith("bsmpm: error:"):
            message = line[len("bsmpm: error: "):]
            break
    if args.keep or verdict:
        with open(os.path.join(tmp, "command"), "w") as f:
            f.write(repr(line) + "\n")
        with open(os.path.join(tmp, "stdout"), "w") as f:
            f.write(out)
        with open(os.path.join(tmp, "stderr"), "w") as f:
            f.write(err)
    # Past the input stage: the run made its output directory.
    reached_setup = returncode == 0 or os.path.isdir(os.path.join(tmp, "out"))
    if not args.keep and not verdict:
        shutil.rmtree(tmp, ignore_errors=True)
    return {"verdict": verdict, "seconds": seconds, "code": returncode,
            "message": message, "directory": tmp,
            "reached_setup": reached_setup}


# Classes whose input stage reads on the first process and sends to the
# others (checkpoints; the output directory's probe).
COMMUNICATING_INPUT = ("resume", "output")


def needs_more_processes(case, serial, first_of_kind):
    """Whether a case that ran at np = 1 with the result @p serial runs at
    np > 1 too (see the module's description)."""
    return (args.every_case_at_every_np or serial["reached_setup"] or
            serial["verdict"] != "" or case.kind in COMMUNICATING_INPUT or
            first_of_kind)


def main():
    names = [c.name for c in CASES]
    assert len(names) == len(set(names)), "duplicate case names"
    shard, shards = (int(k) for k in args.shard.split("/"))
    assert 1 <= shard <= shards, "--shard K/N needs 1 <= K <= N"
    cases = [c for i, c in enumerate(CASES)
             if args.only in c.name and i % shards == shard - 1]
    if args.list:
        for c in cases:
            print(f"{c.name:36s} {c.kind:13s} {expectation(c)}")
        return 0
    processes = [int(n) for n in args.np.split(",")]
    start = time.time()
    serial = [n for n in processes if n == 1]
    parallel = [n for n in processes if n != 1]
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        jobs = [(c, n) for c in cases for n in serial]
        results = dict(zip(jobs, pool.map(lambda j: run(*j), jobs)))
        # The first case of each class in the whole list, whatever the shard.
        first_of_kind = {}
        for c in CASES:
            first_of_kind.setdefault(c.kind, c.name)
        chosen = [c for c in cases if not serial or needs_more_processes(
            c, results[(c, 1)], first_of_kind[c.kind] == c.name)]
        more = [(c, n) for c in chosen for n in parallel]
        results.update(zip(more, pool.map(lambda j: run(*j), more)))
        jobs += more
    total = time.time() - start

    bad = 0
    print(f"{'case':36s} {'class':13s} " +
          " ".join(f"{'np=' + str(n):>14s}" for n in processes) +
          "  expected")
    for c in cases:
        cells = []
        for n in processes:
            r = results.get((c, n))
            if r is None:
                cells.append(f"{'input stage':>14s}")
            elif r["verdict"]:
                bad += 1
                cells.append(f"{'BAD':>9s} {r['seconds']:4.1f}")
            else:
                outcome = "ok" if r["code"] == 0 else "error"
                cells.append(f"{outcome:>9s} {r['seconds']:4.1f}")
        print(f"{c.name:36s} {c.kind:13s} " + " ".join(cells) +
              f"  {expectation(c)[:60]}")
        if args.messages:
            for n in processes:
                if (c, n) in results and results[(c, n)]["message"]:
                    print(f"{'':51s}np={n}: {results[(c, n)]['message'][:200]}")
    for c in cases:
        for n in processes:
            r = results.get((c, n))
            if r and r["verdict"]:
                print(f"\nBAD {c.name} at np={n}: {r['verdict']}"
                      f"\n  (command, stdout and stderr in {r['directory']})")
                if r["message"]:
                    print(f"  message: {r['message']}")
    longest = max(r["seconds"] for r in results.values())
    part = f" (shard {args.shard} of the {len(CASES)})" if shards > 1 else ""
    print(f"\n{len(cases)} cases{part}, {len(jobs)} runs at np = "
          f"{', '.join(str(n) for n in processes)} ({len(cases) * len(processes) - len(jobs)} "
          f"runs of cases that stop in the input stage left out) in {total:.1f} s (longest run {longest:.1f} s, "
          f"timeout {args.timeout:.0f} s): {bad} bad verdict(s)")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
