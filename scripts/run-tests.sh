#!/usr/bin/env bash
# Runs the tests of one built configuration, once per window-system backend, and prints one summary
# line per backend:  [summary] CONFIG BACKEND: P passed, F failed, S skipped of T tests in N s
#   scripts/run-tests.sh CONFIG [BACKEND...]     (default: the configuration's backends, configs.sh)
# Backends: glx (an X server: scripts/start-xvfb.sh), egl (DISPLAY unset, VTK's vtkEGLRenderWindow),
# osmesa (DISPLAY unset, vtkOSOpenGLRenderWindow with Debian 13's libOSMesa). The summary lines are
# also appended to build/test-summary.txt. With CI=true (or AMRSP_REQUIRE_GPU=1) a test that would
# skip fails instead, naming what is missing, and any skip that remains fails the run.
set -Eeuo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
. "$repo/scripts/configs.sh"
config=${1:?usage: scripts/run-tests.sh CONFIG [BACKEND...]}
shift
amrsp_run_where_config_belongs scripts/run-tests.sh "$config" "$@"
# AMRSP_BUILD_DIR and AMRSP_SUMMARY_FILE point a run elsewhere (Testing.SkipBackstop runs this
# script on a ctest folder of its own)
build=${AMRSP_BUILD_DIR:-$repo/build/$config}
summary=${AMRSP_SUMMARY_FILE:-$repo/build/test-summary.txt}
[ -f "$build/CTestTestfile.cmake" ] || { echo "[test] $config is not built (scripts/build.sh $config)" >&2; exit 1; }
backends=("$@")
[ "${#backends[@]}" -gt 0 ] || read -r -a backends <<<"$(amrsp_config_backends "$config")"
jobs=${AMRSP_JOBS:-$(nproc)}
# In CI everything a test needs is installed: a test that would skip (no OpenGL context, no bindless
# on zink, no pvserver/pvbatch/mpiexec/paraview, no ../shared/data) fails instead, naming what is
# missing. People running the tests by hand get skips unless they set it.
if [ "${CI:-}" = true ]; then export AMRSP_REQUIRE_GPU=1; fi
status=0
for backend in "${backends[@]}"; do
  log="$build/ctest-$backend.log"
  # AMRSP_CTEST_ARGS replaces the pass's selection (scripts/repeat-mpi-tests.sh)
  if [ -n "${AMRSP_CTEST_ARGS:-}" ]; then
    read -r -a select <<<"$AMRSP_CTEST_ARGS"
  else
    mapfile -t select < <(amrsp_ctest_selection "$config" "$backend")
  fi
  echo "[test] ctest: $config, backend $backend (log: $log)"
  t0=$SECONDS
  set +e
  (
    if [ "$config" = sanitizers ]; then
      # Mesa and VTK keep allocations to the end (no leak checking); any other finding fails
      export ASAN_OPTIONS=detect_leaks=0:handle_segv=0:handle_sigbus=0:handle_sigfpe=0:handle_abort=0:exitcode=86
      export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
    fi
    case "$backend" in
      glx)
        unset VTK_DEFAULT_OPENGL_WINDOW
        . "$repo/scripts/start-xvfb.sh" >/dev/null || exit 1 ;;
      egl)
        # the ParaView GUI is an X application: its smoke test alone gets an X server
        if [ -n "$(command -v paraview)" ] && . "$repo/scripts/start-xvfb.sh" >/dev/null; then
          export AMRSP_GUI_DISPLAY=$DISPLAY
        fi
        unset DISPLAY
        export VTK_DEFAULT_OPENGL_WINDOW=vtkEGLRenderWindow ;;
      osmesa)
        unset DISPLAY
        export VTK_DEFAULT_OPENGL_WINDOW=vtkOSOpenGLRenderWindow
        lib=$AMRSP_OSMESA_PREFIX/usr/lib/$(amrsp_multiarch)
        [ -e "$lib/libOSMesa.so.8" ] || { echo "FAIL: no libOSMesa.so.8 in $lib (scripts/install-deps.sh unpacks it)"; exit 1; }
        export LD_LIBRARY_PATH="$lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" ;;
      *) echo "unknown backend $backend"; exit 2 ;;
    esac
    # where this pass renders, as the tool reports it: the backend must be the one asked for
    # (with the compute caster: where the driver has no compute shaders the tool says so, and the
    # tests compare the casters only where both run)
    check=$("$build/Tools/amrsp/amrsp" render --size 16x16 --method packing --caster compute \
      -o "$build/backend-check.png" 2>&1) \
      || { echo "$check"; echo "FAIL: amrsp render could not render through $backend"; exit 1; }
    seen=$(printf '%s\n' "$check" | sed -n 's/^backend: //p')
    echo "backend check: $seen; $(printf '%s\n' "$check" | grep '^device: ')"
    if [ "$(printf '%s\n' "$check" | sed -n 's/^caster: //p')" = compute ]; then
      echo "casters check: fragment and compute"
    else
      echo "casters check: fragment only ($(printf '%s\n' "$check" | grep -o 'the OpenGL context[^:]*compute shaders[^:]*' | head -n 1))"
    fi
    # the plugin tests compare the renderer they rendered with to this pass's (PluginTestKit.py)
    AMRSP_EXPECTED_RENDERER=$(printf '%s\n' "$check" | sed -n 's/^device: //p' | head -n 1)
    export AMRSP_EXPECTED_RENDERER
    case "$backend:$seen" in
      glx:GLX*|egl:EGL*|osmesa:OSMesa*) ;;
      *) echo "FAIL: asked for $backend, the tool rendered through '$seen'"; exit 1 ;;
    esac
    cd "$build" && ctest --output-on-failure -j "$jobs" "${select[@]}"
  ) >"$log" 2>&1
  rc=$?
  set -e
  seconds=$((SECONDS - t0))
  total=$(sed -nE 's/.*tests? failed out of ([0-9]+).*/\1/p' "$log" | tail -n 1)
  failed=$(sed -nE 's/.* ([0-9]+) tests? failed out of.*/\1/p' "$log" | tail -n 1)
  # ctest marks a skipped test "***Skipped" on its result line, and lists it again (indented by a
  # tab) under "The following tests did not run"
  skipped=$(grep -cE '^[[:space:]]*[0-9]+/[0-9]+ Test +#[0-9]+: .*\*\*\*Skipped' "$log" || true)
  listed=$(grep -cE '^[[:space:]]*[0-9]+ - .*\(Skipped\)' "$log" || true)
  [ "$listed" -le "$skipped" ] || skipped=$listed
  total=${total:-0} failed=${failed:-0}
  passed=$((total - failed - skipped))
  line="[summary] $config $backend: $passed passed, $failed failed, $skipped skipped of $total tests in $seconds s"
  device=$(sed -n 's/^backend check: //p' "$log" | head -n 1)
  [ -z "$device" ] || line="$line ($device)"
  casters=$(sed -n 's/^casters check: //p' "$log" | head -n 1)
  [ -z "$casters" ] || line="$line; casters: $casters"
  if [ "$rc" != 0 ] || [ "$total" = 0 ]; then
    tail -n 60 "$log"
    amrsp_print_failed_output "$build" "$log"
    status=1
  elif [ "$skipped" != 0 ]; then
    grep -E '\(Skipped\)|SKIPPED' "$log" | head -n 40
    if [ "${CI:-}" = true ]; then
      line="$line (CI: a skip is a failure)"
      status=1
    fi
  fi
  echo "$line"
  echo "$line" >>"$summary"
done
exit $status
