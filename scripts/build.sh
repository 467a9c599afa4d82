#!/usr/bin/env bash
# Configures and builds one configuration of the project (idempotent; reuses the build folder).
#   scripts/build.sh CONFIG   -> build/CONFIG
# CONFIG (scripts/configs.sh): paraview, vtk (Debian 12), trixie-paraview, trixie-vtk (Debian 13),
# forky-paraview, forky-vtk (Debian testing). On a Debian 12 host a trixie-/forky- configuration is
# built inside that release's root (scripts/debian-root.sh; create it with
# `scripts/debian-root.sh SUITE ensure`).
set -Eeuo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
. "$repo/scripts/configs.sh"
config=${1:?usage: scripts/build.sh CONFIG ($AMRSP_ALL_CONFIGS)}
amrsp_run_where_config_belongs scripts/build.sh "$config"
# one compile job more than cores: a job that links or waits on the disk leaves no core idle
jobs=${AMRSP_JOBS:-$(($(nproc) + 1))}
multiarch=$(amrsp_multiarch)
read -r private_vtk private_prefix <<<"$(amrsp_private_vtk "$config")" || true
case "$config" in
  *paraview)
    args=(-DAMRSP_WITH_PARAVIEW=ON) ;;
  vtk|trixie-vtk)
    # dpkg does not own the private prefix: its packages' version (vtk-private-prefix.sh's stamp) is
    # what the Debian package of this configuration depends on
    vtk_version=$(sed -n 's/^version=//p' "$private_prefix/.amrsp/stamp" 2>/dev/null || true)
    args=(-DAMRSP_WITH_PARAVIEW=OFF "-DVTK_DIR=$private_prefix/usr/lib/$multiarch/cmake/vtk-$private_vtk"
      "-DAMRSP_DEBIAN_VTK_DEPENDS=${vtk_version:+libvtk$private_vtk (= $vtk_version), python3-vtk9 (= $vtk_version)}") ;;
  forky-vtk)
    args=(-DAMRSP_WITH_PARAVIEW=OFF) ;;  # the system VTK 9.6, which ParaView 6.1 uses too
  sanitizers)
    # the vtk configuration with AddressSanitizer and UndefinedBehaviorSanitizer
    args=(-DAMRSP_WITH_PARAVIEW=OFF "-DVTK_DIR=$private_prefix/usr/lib/$multiarch/cmake/vtk-$private_vtk"
      -DAMRSP_SANITIZE=ON  # it runs the core and tool tests
      -DAMRSP_WRAP_PYTHON=OFF) ;;  # Python cannot load an AddressSanitizer module
esac
# The VTK configurations wrap the module for Debian's python3-vtk9, which is built for the
# system's python3 (not one an environment manager puts first on PATH)
case "$config" in
  *vtk) [ -x /usr/bin/python3 ] && args+=(-DPython3_EXECUTABLE=/usr/bin/python3) ;;
esac
# The test programs this configuration's passes run (scripts/configs.sh; docs/testing.md,
# "Coverage matrix")
read -r -a test_options <<<"$(amrsp_config_test_options "$config")"
args+=("${test_options[@]}")
# Mapper.ShaderVariants checks the shader sources, which no VTK version changes: once per CI run,
# in the configuration that runs the whole mapper suite on the oldest VTK
[ "$config" = vtk ] && args+=(-DAMRSP_SHADER_VARIANT_TEST=ON) || args+=(-DAMRSP_SHADER_VARIANT_TEST=OFF)
# Tool.CLI.Series under the sanitizers: every series path once (docs/testing.md, "Coverage matrix":
# smoke there; forky-vtk judges the selections, range forms and the 120-change soak)
[ "$config" = sanitizers ] && args+=(-DAMRSP_SERIES_SMOKE=ON) || args+=(-DAMRSP_SERIES_SMOKE=OFF)
# The GPU profile command's smoke test where the GPU bundle's amrsp comes from (forky-vtk), the
# only build the profile runs
case "$config" in
  forky-vtk) args+=(-DAMRSP_GPU_PROFILE_TEST=ON) ;;
  *) args+=(-DAMRSP_GPU_PROFILE_TEST=OFF) ;;
esac
# pvbatch on 4 ranks (more than CI's 2 cores) in the Debian 12 ParaView configuration; the newer
# ParaViews run the same script on 2 ranks (CI time: 33 s of serial tests each)
case "$config" in
  trixie-paraview|forky-paraview) args+=(-DAMRSP_MPI_FOUR_RANKS=OFF) ;;
esac
# After a change inside the library only the library relinks: the programs linked to it load the
# new one (CMAKE_LINK_DEPENDS_NO_SHARED; a changed header recompiles and relinks its programs).
args+=(-DCMAKE_LINK_DEPENDS_NO_SHARED=ON)
# A unity build (about half the time of a build from nothing; CMakeLists.txt). AMRSP_UNITY_BUILD=OFF
# builds one object per source, which rebuilds less after a one-file change.
args+=("-DCMAKE_UNITY_BUILD=${AMRSP_UNITY_BUILD:-ON}")
build="$repo/build/$config"
mkdir -p "$repo/build"
echo "[build] $config -> $build"
cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release -DAMRSP_STRICT_WARNINGS=ON \
  "-DAMRSP_DATA_DIR=${AMRSP_DATA_DIR:-$repo/../shared/data}" "${args[@]}" >"$build.configure.log" 2>&1 \
  || { cat "$build.configure.log"; echo "[build] configure of $config failed" >&2; exit 1; }
cmake --build "$build" -j "$jobs"
