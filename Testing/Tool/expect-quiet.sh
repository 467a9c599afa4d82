#!/bin/sh
# usage: expect-quiet.sh REGEX COMMAND [ARGS...]
# Passes when COMMAND exits 0, its stdout has a line matching REGEX (extended) and its stderr is
# empty: the tool's one-line-error contract means nothing else may reach stderr on success (VTK's
# "bad X server connection" when it probes X before EGL would).
pattern=$1
shift
out=$(mktemp) err=$(mktemp)
"$@" >"$out" 2>"$err"
rc=$?
status=0
if [ "$rc" -ne 0 ]; then echo "FAIL: exit code $rc"; status=1; fi
if ! grep -Eq "$pattern" "$out"; then echo "FAIL: stdout does not match: $pattern"; status=1; fi
if [ -s "$err" ]; then echo "FAIL: stderr is not empty"; status=1; fi
echo "--- stdout:"; cat "$out"; echo "--- stderr:"; cat "$err"
rm -f "$out" "$err"
exit $status
