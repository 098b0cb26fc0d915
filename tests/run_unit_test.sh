#!/bin/sh
# Runs one unit test as deal.II's test macros do (tests/CMakeLists.txt,
# bsmpm_pickup_tests): in an empty directory, deal.II's run_test.sh runs
# the command (the test writes deallog to "output"; a non-zero exit fails
# and prints the output), normalize.pl removes what differs between runs
# (dates, "-0"), and run_test.sh compares "output" with the reference by
# numdiff, failing with the first lines of the difference.
#
# run_unit_test.sh <test> <directory> <reference> <deal.II's scripts>
#   <numdiff> <command>...
set -e
test=$1 directory=$2 reference=$3 scripts=$4 numdiff=$5
shift 5
rm -rf "$directory"
mkdir -p "$directory"
cd "$directory"
sh "$scripts/run_test.sh" run "$test" "$@"
perl -pi "$scripts/normalize.pl" output
sh "$scripts/run_test.sh" diff "$test" "$numdiff" "$reference"
