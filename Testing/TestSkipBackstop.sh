#!/usr/bin/env bash
# The CI backstop of scripts/run-tests.sh on a ctest folder of its own: one test that passes and
# one that exits with CTest's skip code. With CI=true the run must fail and count 1 skipped; with
# the skipping test gone it must pass with 0 skipped; a test that prints SKIPPED: and FAIL: and
# exits 1 is a failure, not a skip.
#   TestSkipBackstop.sh REPO CONFIG BACKEND
# CONFIG is the build folder's name; a folder the scripts did not name (a user's own
# `cmake -B build-vtk`) checks the backstop under a configuration of this system's Debian release
# (the fake suite below needs nothing of the build), or says SKIPPED where none is (exit 125).
set -uo pipefail
repo=$1 config=$2 backend=$3
. "$repo/scripts/configs.sh"
if ! amrsp_config_suite "$config" >/dev/null; then
  host=$(amrsp_host_suite) chosen=
  for c in $AMRSP_ALL_CONFIGS; do
    [ "$(amrsp_config_suite "$c")" = "$host" ] && { chosen=$c; break; }
  done
  if [ -z "$chosen" ] && [ "${AMRSP_REQUIRE_GPU:-0}" = 1 ]; then
    echo "FAIL: required here (AMRSP_REQUIRE_GPU=1): scripts/run-tests.sh runs on Debian 12, 13 or testing; this system is '$host'"
    exit 1
  elif [ -z "$chosen" ]; then
    echo "SKIPPED: scripts/run-tests.sh runs on Debian 12, 13 or testing; this system is '$host'"
    exit 125
  fi
  echo "the build folder '$config' is none of the scripts' configurations: checking the backstop as '$chosen' ($host)"
  config=$chosen
  case "$config" in forky-*) backend=egl ;; *) backend=glx ;; esac
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/Tools/amrsp"
# the backend check of run-tests.sh asks the tool where it rendered: answer as the pass expects
cat >"$work/Tools/amrsp/amrsp" <<'SH'
#!/bin/sh
case "${VTK_DEFAULT_OPENGL_WINDOW:-}" in
  vtkEGLRenderWindow) echo "backend: EGL (fake)" ;;
  vtkOSOpenGLRenderWindow) echo "backend: OSMesa (fake)" ;;
  *) echo "backend: GLX (fake)" ;;
esac
echo "device: none (TestSkipBackstop)"
SH
chmod +x "$work/Tools/amrsp/amrsp"
suite() {  # $1: the CTestTestfile.cmake lines
  # every test labelled so that each configuration's label selection picks it (configs.sh,
  # amrsp_config_labels: each selects tool or everywhere)
  printf '%s\nset_directory_properties(PROPERTIES LABELS "tool;everywhere")\n' "$1" >"$work/CTestTestfile.cmake"
  rm -rf "$work/Testing"
  CI=true AMRSP_BUILD_DIR="$work" AMRSP_SUMMARY_FILE="$work/summary.txt" AMRSP_JOBS=1 \
    "$repo/scripts/run-tests.sh" "$config" "$backend" >"$work/out.txt" 2>&1
  rc=$?
  line=$(grep '^\[summary\]' "$work/out.txt" | tail -n 1)
  echo "exit $rc: $line"
}
status=0
expect() {  # $1 description, $2 expected exit (0 or nonzero), $3 regex the summary must match
  if { [ "$2" = 0 ] && [ "$rc" != 0 ]; } || { [ "$2" != 0 ] && [ "$rc" = 0 ]; } ||
    ! printf '%s\n' "$line" | grep -qE "$3"; then
    echo "FAIL: $1"; cat "$work/out.txt"; status=1
  else
    echo "ok: $1"
  fi
}
suite 'add_test(passes "/bin/sh" "-c" "exit 0")
add_test(skips "/bin/sh" "-c" "exit 125")
set_tests_properties(skips PROPERTIES SKIP_RETURN_CODE 125)'
expect "a skipped test fails the CI run and is counted" 1 ' 1 passed, 0 failed, 1 skipped of 2 tests'
suite 'add_test(passes "/bin/sh" "-c" "exit 0")'
expect "without it the run passes" 0 ' 1 passed, 0 failed, 0 skipped of 1 tests'
suite 'add_test(passes "/bin/sh" "-c" "exit 0")
add_test(lies "/usr/bin/env" "python3" "'"$repo"'/Testing/TestVerdict.py" "--" "/bin/sh" "-c" "echo SKIPPED: x; echo FAIL: y; exit 1")
set_tests_properties(lies PROPERTIES SKIP_RETURN_CODE 125)'
expect "SKIPPED: beside FAIL: and exit 1 is a failure" 1 ' 1 passed, 1 failed, 0 skipped of 2 tests'
exit $status
