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

# The roots are made in the background, from the start: the host's own packages install on one
# core (dpkg), then the host's configurations build and run beside them. They need only
# debootstrap from this host, installed first.
mkdir -p "$repo/build"
if [ "$host" = bookworm ] && ! command -v debootstrap >/dev/null; then
  echo "[test] installing debootstrap for the roots (log: /tmp/amrsp-debootstrap.log)"
  { apt-get -q -o DPkg::Lock::Timeout=600 update \
      && apt-get -q -y -o DPkg::Lock::Timeout=600 install --no-install-recommends debootstrap; } \
    >/tmp/amrsp-debootstrap.log 2>&1 \
    || { tail -n 20 /tmp/amrsp-debootstrap.log; echo "[test] installing debootstrap failed" >&2; exit 1; }
fi
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
echo "[test] installing dependencies (log: /tmp/amrsp-install-deps.log)"
t0=$SECONDS
"$repo/scripts/install-deps.sh" >/tmp/amrsp-install-deps.log 2>&1 \
  || { tail -n 40 /tmp/amrsp-install-deps.log; echo "[test] installing dependencies failed" >&2; exit 1; }
install_seconds=$((SECONDS - t0))

# Formatting, once for every configuration (one clang-format version decides): the self-test shows
# that the check rejects a misformatted file, then every tracked C and C++ file is checked.
# Off Debian 12 there is no clang-format 14: that is reported as skipped, and fails under CI=true.
format_line="[summary] format: every C and C++ file formatted as .clang-format says"
format_rc=0
t0=$SECONDS
"$repo/scripts/check-format.sh" --self-test && "$repo/scripts/check-format.sh" || format_rc=$?
if [ "$format_rc" = 125 ] && [ "${CI:-}" != true ]; then
  format_line="[summary] format: SKIPPED (no clang-format 14 on this system; Debian 12 checks it)"
elif [ "$format_rc" != 0 ]; then
  format_line="[summary] format: FAILED (scripts/check-format.sh lists the files; --fix reformats)"
fi

format_seconds=$((SECONDS - t0))

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
  rm -f "$repo/build/packages/$config.seconds"
  (
    flock 9
    t0=$SECONDS  # the package test's own time, not its wait for the one before it
    "$repo/scripts/package.sh" "$config" || true  # without a .deb, test-package.sh reports the failure
    "$repo/scripts/test-package.sh" "$config"
    rc=$?
    echo "$((SECONDS - t0))" >"$repo/build/packages/$config.seconds"
    exit $rc
  ) 9>"$repo/build/packages/.lock" >"$repo/build/packages/$config.log" 2>&1 &
  package_pids+=("$!:$config")
}
declare -A root_waited
wait_for_root() {  # $1 = suite
  local pid=${root_pid[$1]:-} t0=$SECONDS rc=0
  [ -n "$pid" ] || return 0
  wait "$pid" || rc=$?
  root_waited[$1]=$(( ${root_waited[$1]:-0} + SECONDS - t0 ))
  if [ "$rc" != 0 ]; then
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
declare -A build_seconds ctest_seconds
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
  build_seconds[$config]=$((SECONDS - t0))
  builds+=("$config ${build_seconds[$config]} s")
  [ "$config" = sanitizers ] || start_package_test "$config"
  t0=$SECONDS
  "$repo/scripts/run-tests.sh" "$config" || status=1
  ctest_seconds[$config]=$((SECONDS - t0))
done
for suite in "${roots[@]}"; do wait_for_root "$suite" >/dev/null 2>&1 || true; done
t_tail=$SECONDS
for entry in "${package_pids[@]}"; do
  if ! wait "${entry%%:*}"; then
    status=1
    tail -n 30 "$repo/build/packages/${entry#*:}.log"
  fi
done

package_tail=$((SECONDS - t_tail))

# Phase timings: one line per configuration (wall seconds of its install, root creation, build,
# ctest and package test) and a total line, in build/test-summary.txt and at the end of the output.
# A Debian 12 configuration's install is the host's (shared by paraview, vtk and sanitizers); a
# newer release's install and root are its root's (shared by the release's two configurations, made
# in the background: "waited" is how long the builds waited for it). Package tests run in the
# background, one at a time.
phase_of_root() {  # $1 = suite, $2 = root|install: the seconds debian-root.sh printed, or 0
  sed -n "s/^\[root $1\] phase $2: \([0-9]*\) s$/\1/p" "$repo/build/root-$1.log" 2>/dev/null | tail -n 1 | grep . || echo 0
}
phases=()
sum_builds=0 sum_ctest=0 sum_packages=0 sum_roots=0 sum_waited=0
for config in "${configs[@]}"; do
  suite=$(amrsp_config_suite "$config")
  b=${build_seconds[$config]:-0} c=${ctest_seconds[$config]:-0}
  p=$(cat "$repo/build/packages/$config.seconds" 2>/dev/null || echo 0)
  if [ "$suite" = "$host" ]; then
    line="[phases] $config: install $install_seconds s (this host's, shared), root 0 s (none), build $b s, ctest $c s"
  else
    r=$(phase_of_root "$suite" root) i=$(phase_of_root "$suite" install) w=${root_waited[$suite]:-0}
    line="[phases] $config: install $i s, root $r s (the $suite root's, shared, in the background; waited $w s), build $b s, ctest $c s"
  fi
  [ "$config" = sanitizers ] && line="$line, package 0 s (none)" || line="$line, package $p s (in the background)"
  phases+=("$line")
  sum_builds=$((sum_builds + b)) sum_ctest=$((sum_ctest + c)) sum_packages=$((sum_packages + p))
done
for suite in "${roots[@]}"; do
  sum_roots=$((sum_roots + $(phase_of_root "$suite" root) + $(phase_of_root "$suite" install)))
  sum_waited=$((sum_waited + ${root_waited[$suite]:-0}))
done
total_seconds=$((SECONDS - t_start))
phases+=("[phases] total: $total_seconds s ($((total_seconds / 60)) min) wall; in line: install $install_seconds s, format $format_seconds s, waiting for roots $sum_waited s, builds $sum_builds s, ctest $sum_ctest s, waiting for package tests at the end $package_tail s; in the background: roots $sum_roots s, package tests $sum_packages s")
printf '%s\n' "${phases[@]}" >>"$repo/build/test-summary.txt"

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
