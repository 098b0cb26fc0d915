#!/bin/sh
# Runs a command that must fail cleanly: a non-zero exit code that is not a
# crash (signal), a message starting with "bsmpm: error:", and the expected
# text in it. Usage: check_error.sh "expected text" command [args...]
expected="$1"
shift
workdir=$(mktemp -d)
cd "$workdir" || exit 1
"$@" > output 2>&1
code=$?
status=0
if [ "$code" -eq 0 ]; then
  echo "FAIL: the command succeeded but should have failed"
  status=1
elif [ "$code" -ge 128 ]; then
  echo "FAIL: the command crashed (exit code $code)"
  status=1
elif ! grep -q "^bsmpm: error:" output; then
  echo "FAIL: no 'bsmpm: error:' message"
  status=1
elif ! grep -qF -- "$expected" output; then
  echo "FAIL: the message does not contain: $expected"
  status=1
fi
echo "exit code $code; output:"
cat output
rm -rf "$workdir"
exit $status
