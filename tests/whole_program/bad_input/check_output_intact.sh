#!/bin/sh
# A run that stops with an error in load step N must leave the files of the
# steps before it complete and readable: no temporary file, every file the
# collections name present, the last .pvtu's pieces present; and
# summary.json with those steps, status "failed", the failed step and its
# message, with the ParaView output on and off (Output/Interval = 0).
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
check_summary() {
  python3 - "$1" "$3" <<'PY' || status=1
import json, sys
summary = json.load(open(sys.argv[1]))
done = [s["step"] for s in summary["steps"]]
want = list(range(1, int(sys.argv[2]) + 1))
problems = []
if done != want:
    problems.append(f"steps {done}, expected {want}")
if summary.get("status") != "failed":
    problems.append(f"status {summary.get('status')!r}, expected 'failed'")
if summary.get("failed_step") != int(sys.argv[2]) + 1:
    problems.append(f"failed_step {summary.get('failed_step')}")
if "left the background grid" not in summary.get("error", ""):
    problems.append(f"error {summary.get('error')!r}")
for p in problems:
    print("FAIL: summary.json: " + p)
sys.exit(1 if problems else 0)
PY
}
check_summary "$dir/out/summary.json" "" "$3"
if "$bsmpm" "$prm" --set "Output/Directory=$dir/quiet" --set "Output/Interval=0" \
    > "$dir/log" 2>&1; then
  echo "FAIL: the run without output did not stop"; status=1
fi
check_summary "$dir/quiet/summary.json" "" "$3"
[ $status -eq 0 ] && echo "output and summary of step $last intact"
exit $status
