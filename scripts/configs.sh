# shellcheck shell=bash
# The project's build configurations, sourced by build.sh, run-tests.sh and test.sh.
#
#   config           Debian release (suite)   ParaView / VTK                       backends tested
#   paraview         12 bookworm (this host)  ParaView 5.11, its bundled VTK 9.2   GLX (Xvfb)
#   vtk              12 bookworm (this host)  plain VTK 9.1 (private prefix)       GLX (Xvfb)
#   trixie-paraview  13 trixie                ParaView 5.13, its bundled VTK 9.3   GLX (Xvfb)
#   trixie-vtk       13 trixie                plain VTK 9.3 (private prefix)       GLX (Xvfb)
#   forky-paraview   testing forky            ParaView 6.1 on the system VTK 9.6   EGL, OSMesa (no X server)
#   forky-vtk        testing forky            plain VTK 9.6 (the same VTK)         EGL, OSMesa (no X server)
#
# A configuration whose suite is not the running system's is built and tested inside a Debian root
# of that suite (scripts/debian-root.sh), on a Debian 12 host only.

AMRSP_ALL_CONFIGS="paraview vtk sanitizers trixie-paraview trixie-vtk forky-paraview forky-vtk"

# The running system's codename (bookworm, trixie, forky), or what os-release says.
amrsp_host_suite() {
  local codename
  codename=$(. /etc/os-release 2>/dev/null && echo "${VERSION_CODENAME:-unknown}")
  printf '%s\n' "$codename"
}

# The multiarch library folder name (x86_64-linux-gnu on amd64).
amrsp_multiarch() {
  dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || echo x86_64-linux-gnu
}

amrsp_config_suite() {  # $1 = config
  case "$1" in
    paraview|vtk|sanitizers) echo bookworm ;;
    trixie-*) echo trixie ;;
    forky-*) echo forky ;;
    *) return 1 ;;
  esac
}

# The configurations this system runs by default: on Debian 12 all of them (the newer ones in
# roots), on Debian 13 or testing those of that release.
amrsp_default_configs() {
  case "$(amrsp_host_suite)" in
    bookworm) echo "$AMRSP_ALL_CONFIGS" ;;
    trixie) echo "trixie-paraview trixie-vtk" ;;
    forky) echo "forky-paraview forky-vtk" ;;
    *) return 1 ;;
  esac
}

# The one line for an unsupported system.
amrsp_unsupported() {
  echo "this is '$(. /etc/os-release 2>/dev/null && echo "${PRETTY_NAME:-unknown}")'; supported: Debian 12" \
    "bookworm (all configurations), Debian 13 trixie (ParaView 5.13, VTK 9.3), Debian testing forky" \
    "(ParaView 6.1, VTK 9.6)"
}

# Debian's plain VTK that a configuration builds against from a private prefix, since that
# release's python3-paraview Conflicts with python3-vtk9 (scripts/vtk-private-prefix.sh); nothing
# for the others. Prints "VERSION PREFIX".
amrsp_private_vtk() {  # $1 = config
  case "$1" in
    vtk|sanitizers) echo "9.1 ${AMRSP_VTK91_PREFIX:-/opt/amrsp/vtk-9.1}" ;;
    trixie-vtk) echo "9.3 ${AMRSP_VTK93_PREFIX:-/opt/amrsp/vtk-9.3}" ;;
  esac
}

# The window-system backends whose ctest passes a configuration runs, the first being the full suite.
amrsp_config_backends() {  # $1 = config
  case "$1" in
    forky-*) echo "egl osmesa" ;;
    *) echo "glx" ;;
  esac
}

# What each configuration tests. docs/testing.md's "Coverage matrix" says why, feature by feature,
# and Testing.CoverageMatrix checks it against what these functions select. The rule: code that is
# the same in every configuration (the GL-free core, the shader logic on llvmpipe, the command
# line) is tested fully in one configuration; code that differs between VTK or ParaView versions or
# window systems is tested in every configuration where it differs. The full suites run on the
# oldest and the newest VTK: on VTK 9.1 (GLX) vtk runs the core and the mapper's suites and the
# sanitizers build, on the same VTK, compiler and Xvfb, the core and the tool's suite (the tool's
# tests run once there, not twice); forky-vtk runs the tool's and the mapper's suites on VTK 9.6
# (EGL and OSMesa). Elsewhere the tests labelled with what differs there
# (cmake/SinglePassAMRTestLabels.cmake: readers, data-model, context, rendering, vtk-amr,
# everywhere), and every ParaView test (plugin) in every ParaView configuration.
# The ctest labels of a configuration's first backend pass: an anchored regular expression, or
# nothing for every test.
amrsp_config_labels() {  # $1 = config
  case "$1" in
    vtk) echo "" ;;
    sanitizers) echo "^(core|tool)$" ;;  # the core and tool tests, the fuzzer among them
    paraview) echo "^(plugin|plugin-datasets|readers|data-model|context|vtk-amr|everywhere)$" ;;
    trixie-paraview) echo "^(plugin|readers|data-model|context|vtk-amr|everywhere)$" ;;
    trixie-vtk) echo "^(python|consumer|readers|data-model|context|rendering|everywhere)$" ;;
    forky-paraview) echo "^(plugin|everywhere)$" ;;  # forky-vtk runs the suites on this same VTK
    forky-vtk) echo "^(tool|mapper|python|consumer)$" ;;
  esac
}

# The ctest arguments of one backend pass, one per line (scripts/run-tests.sh and
# Testing.CoverageMatrix use them). OSMesa (a second way to render with no X server, Debian 13's
# Mesa 25.0 through VTK 9.6's OSMesa window) runs the tests of the context and of the renders
# through VTK's OpenGL classes, and one pvbatch and one pvpython test. Mesa's OSMesa is llvmpipe
# only: the zink (bindless) tests belong to the EGL pass.
amrsp_ctest_selection() {  # $1 = config, $2 = backend
  local labels
  case "$2" in
    osmesa)
      case "$1" in
        *paraview) printf '%s\n' -R '^Plugin\.MPI\.np2\.enzo$|^Plugin\.Representation\.enzo$' ;;
        *) printf '%s\n' -L '^(context|rendering)$' -E 'Bindless|Zink' ;;
      esac ;;
    *)
      labels=$(amrsp_config_labels "$1")
      [ -z "$labels" ] || printf '%s\n' -L "$labels" ;;
  esac
}

# Whether a configuration has a Debian package (scripts/package.sh, scripts/test-package.sh):
# exit status 0 for all but the sanitizers build.
amrsp_config_packaged() {  # $1 = config
  [ "$1" != sanitizers ]
}

# CMake options of a configuration's tests (scripts/build.sh): test programs that no pass of the
# configuration runs are not built.
amrsp_config_test_options() {  # $1 = config
  case "$1" in
    vtk)  # the core's and the tool's tests on this VTK 9.1: the sanitizers build's (the same VTK,
      # compiler and Xvfb); this -O3 core is checked here by every image test against the reference
      echo "-DAMRSP_CORE_TESTS=OFF -DAMRSP_MAPPER_TESTS=ON -DAMRSP_MAPPER_IMAGE_TESTS=ON -DAMRSP_TOOL_TESTS=OFF" ;;
    sanitizers) echo "-DAMRSP_CORE_TESTS=ON -DAMRSP_MAPPER_TESTS=OFF" ;;
    paraview|trixie-paraview)  # the mapper's context and data-model tests only
      echo "-DAMRSP_CORE_TESTS=OFF -DAMRSP_MAPPER_TESTS=ON -DAMRSP_MAPPER_IMAGE_TESTS=OFF" ;;
    forky-paraview) echo "-DAMRSP_CORE_TESTS=OFF -DAMRSP_MAPPER_TESTS=OFF -DAMRSP_TOOL_TESTS=OFF" ;;
    *) echo "-DAMRSP_CORE_TESTS=OFF -DAMRSP_MAPPER_TESTS=ON -DAMRSP_MAPPER_IMAGE_TESTS=ON" ;;
  esac
}

# Where the OSMesa library lives inside a forky root or on Debian testing: Debian 13's libosmesa6
# (Mesa 25.0, the last Mesa with OSMesa) unpacked by install-deps.sh into a private prefix.
AMRSP_OSMESA_PREFIX=${AMRSP_OSMESA_PREFIX:-/opt/amrsp/osmesa}

# Makes SCRIPT (relative to the repository) run where CONFIG belongs: returns when CONFIG's suite
# is this system's; otherwise, on a Debian 12 host, runs `SCRIPT CONFIG ARGS...` inside that suite's
# root (scripts/debian-root.sh) in place of the caller (exec). Exits 2 for an unknown configuration
# or a system that can neither build it nor host its root.
amrsp_run_where_config_belongs() {  # $1 = script, $2 = config, rest = its other arguments
  local script=$1 config=$2 suite host repo
  suite=$(amrsp_config_suite "$config") \
    || { echo "$script: unknown configuration '$config' ($AMRSP_ALL_CONFIGS)" >&2; exit 2; }
  host=$(amrsp_host_suite)
  [ "$suite" != "$host" ] || return 0
  [ "$host" = bookworm ] \
    || { echo "$script: $config needs Debian $suite, or a root of it on Debian 12; this is $host" >&2; exit 2; }
  repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
  shift 2
  exec "$repo/scripts/debian-root.sh" "$suite" run "$script" "$config" "$@"
}

# Prints the recorded output of every test the ctest log lists as failed (the last 80 lines of
# each), so that a CI log that keeps only stdout still says why a test failed.
amrsp_print_failed_output() {  # $1 = build directory, $2 = ctest log
  local last="$1/Testing/Temporary/LastTest.log" name
  [ -f "$last" ] || return 0
  sed -nE 's/^[[:space:]]*[0-9]+ - ([^ ]+) \((Failed|Timeout|.*Exception.*|Not Run)\).*/\1/p' "$2" |
    while read -r name; do
      echo "[test] ---- output of $name ----"
      awk -v name="$name" '
        $0 ~ ("Testing: " name "$") { on = 1 }
        on { print }
        on && index($0, "\"" name "\" end time") { exit }' "$last" | tail -n 80
    done
}
