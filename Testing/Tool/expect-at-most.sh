#!/bin/sh
# usage: expect-at-most.sh [--after=TEXT] 'LABEL=BOUND' ['LABEL' ...] -- COMMAND [ARGS...]
# Passes when COMMAND exits 0 and, for each LABEL=BOUND (LABEL a fixed string), the first number
# after LABEL on the first line of its stdout containing LABEL is at most BOUND; a LABEL without a
# bound must appear in stdout. A missing label or number fails. --after=TEXT: the labels are
# looked for only after the first line containing TEXT (one method's block of bench's JSON), which
# must be there. With
# AMRSP_REQUIRE_GPU unset, a command that says it cannot render here is reported as skipped (125).
after=""
case "${1:-}" in --after=*) after=${1#--after=}; shift ;; esac
checks=""
while [ "$#" -gt 0 ] && [ "$1" != "--" ]; do checks="$checks
$1"; shift; done
[ "$1" = "--" ] || { echo "usage: expect-at-most.sh 'LABEL=BOUND'... -- COMMAND"; exit 2; }
shift
out=$(mktemp) err=$(mktemp)
"$@" >"$out" 2>"$err"
rc=$?
echo "--- stdout:"; cat "$out"; echo "--- stderr:"; cat "$err"
# (bench reports a method that cannot render in its JSON, render on stderr)
if grep -qh "cannot render here" "$err" "$out"; then
  if [ "${AMRSP_REQUIRE_GPU:-}" = 1 ]; then
    echo "FAIL: required here (AMRSP_REQUIRE_GPU=1) but missing: an OpenGL context"; rm -f "$out" "$err"; exit 1
  fi
  echo "SKIPPED: a GPU method cannot render here"; rm -f "$out" "$err"; exit 125
fi
status=0
if [ "$rc" -ne 0 ]; then echo "FAIL: exit code $rc"; status=1; fi
if [ -n "$after" ]; then
  if ! grep -qF -- "$after" "$out"; then
    echo "FAIL: '$after' not printed"; rm -f "$out" "$err"; exit 1
  fi
  scoped=$(mktemp)
  awk -v t="$after" 'on { print } !on && index($0, t) { on = 1 }' "$out" >"$scoped"
  mv "$scoped" "$out"
  echo "(checks after the line with '$after')"
fi
printf '%s\n' "$checks" | while IFS= read -r check; do
  [ -n "$check" ] || continue
  case "$check" in
    *=*) ;;
    *) if grep -qF -- "$check" "$out"; then echo "ok: '$check' printed"; continue; fi
       echo "FAIL: '$check' not printed"; exit 1 ;;
  esac
  label=${check%=*} bound=${check##*=}
  value=$(grep -F -m 1 -- "$label" "$out" | awk -v l="$label" '{
      i = index($0, l); rest = substr($0, i + length(l));
      if (match(rest, /-?[0-9]+(\.[0-9]+)?([eE][-+]?[0-9]+)?/)) print substr(rest, RSTART, RLENGTH) }')
  if [ -z "$value" ]; then echo "FAIL: no number after '$label'"; exit 1; fi
  if awk -v v="$value" -v b="$bound" 'BEGIN { exit !(v <= b) }'; then
    echo "ok: $label $value (bound $bound)"
  else
    echo "FAIL: $label $value is above the bound $bound"; exit 1
  fi
done || status=1
rm -f "$out" "$err"
exit $status
