#!/bin/sh
# usage: expect-error.sh REGEX COMMAND [ARGS...]
# Passes when COMMAND exits non-zero (but not by a signal), prints nothing on stdout, and prints
# exactly one line on stderr, of the form "amrsp: error: ..." matching REGEX.
pattern=$1
shift
out=$(mktemp) err=$(mktemp)
"$@" >"$out" 2>"$err"
rc=$?
lines=$(wc -l <"$err")
status=0
if [ "$rc" -eq 0 ]; then echo "FAIL: exit code 0"; status=1; fi
if [ "$rc" -ge 128 ]; then echo "FAIL: killed by signal $((rc - 128))"; status=1; fi
if [ "$lines" -ne 1 ]; then echo "FAIL: $lines lines on stderr (want 1)"; status=1; fi
if ! grep -Eq "^amrsp: error: .*$pattern" "$err"; then echo "FAIL: stderr does not match: $pattern"; status=1; fi
if [ -s "$out" ]; then echo "FAIL: unexpected stdout"; status=1; fi
echo "--- stderr:"; cat "$err"
rm -f "$out" "$err"
exit $status
