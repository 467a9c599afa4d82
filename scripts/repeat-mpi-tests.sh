#!/usr/bin/env bash
# Runs every multi-rank and in-situ test (ctest label mpi: Plugin.MPI.*, Plugin.Defaults.MPI,
# InSitu.*) N times in a row in each ParaView configuration, through scripts/run-tests.sh (the same
# X server, backend and environment as the normal run), and prints how often each test passed.
# Not part of scripts/test.sh: a check that the tests are not flaky (docs/testing.md, "Flakiness").
#   scripts/repeat-mpi-tests.sh [-n N] [-R REGEX] [CONFIG...]   (default: 20 times, every ParaView
#                                  configuration of this system; each must be built; -R: only the
#                                  mpi tests whose names match REGEX, as ctest -R reads it; no spaces)
# With AMRSP_REPEAT_LOAD=K, K busy processes run beside the tests (a loaded machine).
# Exit status: 0 when every run of every test passed.
set -Eeuo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
. "$repo/scripts/configs.sh"
times=20
select=('-L' '^mpi$')
while [ "$#" -gt 0 ]; do
  case "$1" in
    -n) times=${2:?-n needs a number}; shift 2 ;;
    -R) select+=('-R' "${2:?-R needs a regular expression}"); shift 2 ;;
    *) break ;;
  esac
done
configs=("$@")
if [ "${#configs[@]}" = 0 ]; then
  for c in $(amrsp_default_configs); do
    case "$c" in *paraview) configs+=("$c") ;; esac
  done
fi
load_pids=()
stop_load() { [ "${#load_pids[@]}" = 0 ] || kill "${load_pids[@]}" 2>/dev/null || true; }
trap stop_load EXIT
for _ in $(seq 1 "${AMRSP_REPEAT_LOAD:-0}"); do
  (while :; do :; done) &
  load_pids+=("$!")
done
cd "$repo"  # the summary file's path below is relative: the same inside a Debian root
status=0
for config in "${configs[@]}"; do
  backend=$(amrsp_config_backends "$config" | cut -d' ' -f1)
  out="$repo/build/repeat-mpi/$config"
  rm -rf "$out"
  mkdir -p "$out"
  declare -A passed=() failed=()
  # only the mpi tests this configuration's normal pass selects (its labels; ctest ANDs two -L)
  config_select=("${select[@]}")
  labels=$(amrsp_config_labels "$config")
  [ -z "$labels" ] || config_select+=('-L' "$labels")
  for i in $(seq 1 "$times"); do
    AMRSP_CTEST_ARGS="${config_select[*]}" AMRSP_SUMMARY_FILE="build/repeat-mpi/$config/summary.txt" \
      "$repo/scripts/run-tests.sh" "$config" "$backend" >"$out/run-$i.log" 2>&1 || true
    log="$repo/build/$config/ctest-$backend.log"
    cp "$log" "$out/ctest-$i.log" 2>/dev/null || true
    while read -r name verdict; do
      if [ "$verdict" = Passed ]; then
        passed[$name]=$(( ${passed[$name]:-0} + 1 ))
      else
        failed[$name]=$(( ${failed[$name]:-0} + 1 ))
        echo "[repeat] $config run $i: $name $verdict (log: ${out#"$repo/"}/ctest-$i.log)"
      fi
    done < <(sed -nE 's/^ *[0-9]+\/[0-9]+ Test +#[0-9]+: ([^ ]+) [.]+[* ]*([A-Za-z]+).*/\1 \2/p' "$out/ctest-$i.log" 2>/dev/null)
  done
  names=$(printf '%s\n' "${!passed[@]}" "${!failed[@]}" | sort -u)
  [ -n "$names" ] || { echo "[repeat] $config: no mpi test ran (see ${out#"$repo/"}/run-1.log)"; status=1; }
  for name in $names; do
    p=${passed[$name]:-0}
    line="[repeat] $config: $name passed $p of $times"
    echo "$line" | tee -a "$out/counts.txt"
    [ "$p" = "$times" ] || status=1
  done
  unset passed failed
done
exit $status
