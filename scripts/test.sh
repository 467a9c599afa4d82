#!/usr/bin/env bash
# README command 2: installs what is missing, builds every configuration and runs every test of each,
# then prints one summary line per configuration and backend (scripts/configs.sh lists them).
#
# On Debian 12 that is all seven configurations: paraview, vtk and sanitizers on the host (GLX,
# Xvfb), and, in Debian roots that scripts/debian-root.sh creates or reuses under
# /var/cache/amrsp/roots, trixie-paraview / trixie-vtk (ParaView 5.13 and plain VTK 9.3, GLX) and
# forky-paraview / forky-vtk (ParaView 6.1 and plain VTK 9.6, with no X server: EGL, then OSMesa).
# On Debian 13 or testing: that release's configurations.
#   AMRSP_CONFIGS="paraview forky-vtk" scripts/test.sh     # a subset, for a quicker local run
#   AMRSP_JOBS=N                                           # parallel build and ctest jobs
set -Eeuo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
. "$repo/scripts/configs.sh"
t_start=$SECONDS
host=$(amrsp_host_suite)
default=$(amrsp_default_configs) || { echo "[test] $(amrsp_unsupported)" >&2; exit 1; }
read -r -a configs <<<"${AMRSP_CONFIGS:-$default}"
roots=()
for config in "${configs[@]}"; do
  suite=$(amrsp_config_suite "$config") \
    || { echo "[test] unknown configuration '$config' (AMRSP_CONFIGS; known: $AMRSP_ALL_CONFIGS)" >&2; exit 2; }
  if [ "$suite" != "$host" ]; then
    [ "$host" = bookworm ] || { echo "[test] $config needs Debian $suite (or a Debian 12 host with roots)" >&2; exit 2; }
    case " ${roots[*]} " in *" $suite "*) ;; *) roots+=("$suite") ;; esac
  fi
done

echo "[test] installing dependencies (log: /tmp/amrsp-install-deps.log)"
"$repo/scripts/install-deps.sh" >/tmp/amrsp-install-deps.log 2>&1 \
  || { tail -n 40 /tmp/amrsp-install-deps.log; echo "[test] installing dependencies failed" >&2; exit 1; }

# Formatting, once for every configuration (one clang-format version decides): the self-test shows
# that the check rejects a misformatted file, then every tracked C and C++ file is checked.
# Off Debian 12 there is no clang-format 14: that is reported as skipped, and fails under CI=true.
format_line="[summary] format: every C and C++ file formatted as .clang-format says"
format_rc=0
"$repo/scripts/check-format.sh" --self-test && "$repo/scripts/check-format.sh" || format_rc=$?
if [ "$format_rc" = 125 ] && [ "${CI:-}" != true ]; then
  format_line="[summary] format: SKIPPED (no clang-format 14 on this system; Debian 12 checks it)"
elif [ "$format_rc" != 0 ]; then
  format_line="[summary] format: FAILED (scripts/check-format.sh lists the files; --fix reformats)"
fi

# The roots are prepared in the background while the host's configurations build and run.
mkdir -p "$repo/build"
declare -A root_pid
for suite in "${roots[@]}"; do
  echo "[test] preparing the Debian $suite root in the background (log: build/root-$suite.log)"
  "$repo/scripts/debian-root.sh" "$suite" ensure >"$repo/build/root-$suite.log" 2>&1 &
  root_pid[$suite]=$!
done
# The Debian packages (scripts/package.sh) are installed into clean roots of their releases
# (scripts/test-package.sh), on a Debian 12 host: the clean roots are made in the background too.
packaged=()
for config in "${configs[@]}"; do
  [ "$config" = sanitizers ] || packaged+=("$config")
done
if [ "$host" = bookworm ] && [ "${#packaged[@]}" -gt 0 ]; then
  clean_suites=()
  for config in "${packaged[@]}"; do
    suite=$(amrsp_config_suite "$config")
    case " ${clean_suites[*]} " in *" $suite "*) ;; *) clean_suites+=("$suite") ;; esac
  done
  echo "[test] making clean roots (${clean_suites[*]}) for the package tests in the background (log: build/clean-roots.log)"
  ( for suite in "${clean_suites[@]}"; do "$repo/scripts/debian-root.sh" "$suite" clean-ensure || true; done ) \
    >"$repo/build/clean-roots.log" 2>&1 &
fi
# A configuration's package is built and tested in the background as soon as the configuration is
# built, while its tests run (one package test at a time: they share apt caches).
package_pids=()
start_package_test() {  # $1 = config
  local config=$1
  if [ "$host" != bookworm ]; then
    echo "[summary] $config package: SKIPPED (clean roots are made on a Debian 12 host)" >>"$repo/build/test-summary.txt"
    [ "${CI:-}" != true ] || status=1
    return 0
  fi
  mkdir -p "$repo/build/packages"
  (
    flock 9
    "$repo/scripts/package.sh" "$config" || true  # without a .deb, test-package.sh reports the failure
    "$repo/scripts/test-package.sh" "$config"
  ) 9>"$repo/build/packages/.lock" >"$repo/build/packages/$config.log" 2>&1 &
  package_pids+=("$!:$config")
}
wait_for_root() {  # $1 = suite
  local pid=${root_pid[$1]:-}
  [ -n "$pid" ] || return 0
  if ! wait "$pid"; then
    tail -n 40 "$repo/build/root-$1.log" >&2
    echo "[test] preparing the Debian $1 root failed" >&2
    return 1
  fi
  root_pid[$1]=
  sed -n 's/^/[test] /p' "$repo/build/root-$1.log" | tail -n 4
}

rm -f "$repo/build/test-summary.txt"
status=0
echo "$format_line" >>"$repo/build/test-summary.txt"
case "$format_line" in *FAILED*) status=1 ;; esac
builds=()
for config in "${configs[@]}"; do
  suite=$(amrsp_config_suite "$config")
  if ! wait_for_root "$suite"; then
    echo "[summary] $config: not built (the $suite root could not be prepared)" >>"$repo/build/test-summary.txt"
    status=1
    continue
  fi
  t0=$SECONDS
  if ! "$repo/scripts/build.sh" "$config" >"$repo/build/build-$config.log" 2>&1; then
    tail -n 60 "$repo/build/build-$config.log"
    echo "[summary] $config: build FAILED (log: build/build-$config.log)" >>"$repo/build/test-summary.txt"
    status=1
    continue
  fi
  builds+=("$config $((SECONDS - t0)) s")
  [ "$config" = sanitizers ] || start_package_test "$config"
  "$repo/scripts/run-tests.sh" "$config" || status=1
done
for suite in "${roots[@]}"; do wait_for_root "$suite" >/dev/null 2>&1 || true; done
for entry in "${package_pids[@]}"; do
  if ! wait "${entry%%:*}"; then
    status=1
    tail -n 30 "$repo/build/packages/${entry#*:}.log"
  fi
done

echo "[test] build times: $(IFS=,; echo "${builds[*]}")"
echo "[test] summary ($(( (SECONDS - t_start) / 60 )) min in all):"
cat "$repo/build/test-summary.txt"
if [ "$status" = 0 ]; then
  echo "[test] every test of ${#configs[@]} configurations passed"
else
  echo "[test] FAILED" >&2
fi
# the closing line: every ctest pass of every configuration added up
sed -nE 's/.*: ([0-9]+) passed, ([0-9]+) failed, ([0-9]+) skipped of .*/\1 \2 \3/p' "$repo/build/test-summary.txt" \
  | awk '{p += $1; f += $2; s += $3} END {printf "tests: %d passed, %d failed, %d skipped\n", p, f, s}'
exit $status
