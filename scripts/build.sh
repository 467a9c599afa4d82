#!/usr/bin/env bash
# Configures and builds one configuration of the project (idempotent; reuses the build folder).
#   scripts/build.sh paraview   -> build/paraview : against ParaView 5.11 (VTK 9.2), with the plugin
#   scripts/build.sh vtk        -> build/vtk      : against Debian's plain VTK 9.1 (private prefix)
set -Eeuo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
config=${1:?usage: scripts/build.sh paraview|vtk}
jobs=${AMRSP_JOBS:-$(nproc)}
multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || echo x86_64-linux-gnu)
case "$config" in
  paraview)
    args=(-DAMRSP_WITH_PARAVIEW=ON) ;;
  vtk)
    prefix=${AMRSP_VTK91_PREFIX:-/opt/amrsp/vtk-9.1}
    args=(-DAMRSP_WITH_PARAVIEW=OFF "-DVTK_DIR=$prefix/usr/lib/$multiarch/cmake/vtk-9.1") ;;
  *)
    echo "scripts/build.sh: unknown configuration '$config' (paraview or vtk)" >&2; exit 2 ;;
esac
build="$repo/build/$config"
mkdir -p "$repo/build"
echo "[build] $config -> $build"
cmake -S "$repo" -B "$build" -DCMAKE_BUILD_TYPE=Release \
  "-DAMRSP_DATA_DIR=${AMRSP_DATA_DIR:-$repo/../shared/data}" "${args[@]}" >"$build.configure.log" 2>&1 \
  || { cat "$build.configure.log"; echo "[build] configure of $config failed" >&2; exit 1; }
cmake --build "$build" -j "$jobs"
