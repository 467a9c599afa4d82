#!/bin/sh
# usage: expect-output.sh REGEX COMMAND [ARGS...]
# Passes when COMMAND exits 0 and its stdout has a line matching REGEX (extended). When the
# command says it cannot render here (no OpenGL context), prints "SKIPPED: ..." and exits 125, or,
# with AMRSP_REQUIRE_GPU=1 (CI), fails.
pattern=$1
shift
out=$(mktemp) err=$(mktemp)
"$@" >"$out" 2>"$err"
rc=$?
if grep -q "cannot render here" "$err"; then
  if [ "${AMRSP_REQUIRE_GPU:-}" = 1 ]; then
    echo "FAIL: required here (AMRSP_REQUIRE_GPU=1) but missing: $(cat "$err")"; rm -f "$out" "$err"; exit 1
  fi
  echo "SKIPPED: $(cat "$err")"; rm -f "$out" "$err"; exit 125
fi
status=0
if [ "$rc" -ne 0 ]; then echo "FAIL: exit code $rc"; status=1; fi
if ! grep -Eq "$pattern" "$out"; then echo "FAIL: stdout does not match: $pattern"; status=1; fi
echo "--- stdout:"; cat "$out"; echo "--- stderr:"; cat "$err"
rm -f "$out" "$err"
exit $status
