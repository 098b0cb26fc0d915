#!/usr/bin/env python3
"""doc/parameters.md must be what scripts/parameter-reference writes from
`bsmpm --print-parameters`: a help string changed in a declare_parameters()
without the reference regenerated fails here, with the difference and the
command that regenerates it.

Usage: parameter_reference.py --bsmpm BSMPM --source-directory ROOT
"""
import argparse
import os
import subprocess
import sys

parser = argparse.ArgumentParser()
parser.add_argument("--bsmpm", required=True)
parser.add_argument("--source-directory", required=True)
args = parser.parse_args()

script = os.path.join(args.source_directory, "scripts", "parameter-reference")
reference = os.path.join(args.source_directory, "doc", "parameters.md")
result = subprocess.run([sys.executable, script, "--bsmpm", args.bsmpm,
                         "--output", reference, "--check"])
if result.returncode == 0:
    print(f"{reference} is current")
sys.exit(result.returncode)
