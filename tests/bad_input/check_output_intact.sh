#!/bin/sh
# A run that stops with an error in load step N must leave the files of the
# steps before it complete and readable: no temporary file, every file the
# collections name present, the last .pvtu's pieces present.
# Usage: check_output_intact.sh BSMPM PRM LAST_COMPLETE_STEP
bsmpm=$1; prm=$2; last=$(printf "%04d" "$3")
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
if "$bsmpm" "$prm" --set "Output/Directory=$dir/out" > "$dir/log" 2>&1; then
  echo "FAIL: the run did not stop"; exit 1
fi
cat "$dir/log" | tail -n 2
status=0
if ls "$dir/out" | grep -q tmp; then
  echo "FAIL: temporary files left behind:"; ls "$dir/out" | grep tmp; status=1
fi
for pvd in "$dir"/out/*.pvd; do
  for f in $(sed -n 's/.*file="\([^"]*\)".*/\1/p' "$pvd"); do
    [ -f "$dir/out/$f" ] || { echo "FAIL: $pvd names missing $f"; status=1; }
  done
done
grep -q "points-$last.pvtu" "$dir/out/solution.pvd" ||
  { echo "FAIL: solution.pvd lacks step $last"; status=1; }
for piece in $(sed -n 's/.*Source="\([^"]*\)".*/\1/p' "$dir/out/points-$last.pvtu"); do
  [ -s "$dir/out/$piece" ] || { echo "FAIL: piece $piece missing"; status=1; }
done
grep -q "</VTKFile>" "$dir/out/points-$last.pvtu" || { echo "FAIL: truncated record"; status=1; }
[ $status -eq 0 ] && echo "output of step $last intact"
exit $status
