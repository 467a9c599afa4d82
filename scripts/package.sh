#!/usr/bin/env bash
# Builds the Debian package of one configuration with CPack (cmake/SinglePassAMRDebianPackage.cmake)
# from its build folder (scripts/build.sh CONFIG first):
#   scripts/package.sh CONFIG   -> build/packages/CONFIG/<name>_<version>_<arch>.deb
#   paraview, trixie-paraview, forky-paraview: singlepassamr-paraview-plugin (the ParaView plugin)
#   vtk, trixie-vtk, forky-vtk: singlepassamr-vtk (the VTK module, its Python package, the amrsp tool)
# Each depends on the exact Debian version of the ParaView or VTK the build used; a build whose
# ParaView/VTK dpkg does not know is refused. scripts/test-package.sh installs the package into a
# clean root of the same release and renders with it.
set -Eeuo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
. "$repo/scripts/configs.sh"
config=${1:?usage: scripts/package.sh CONFIG ($AMRSP_ALL_CONFIGS)}
[ "$config" != sanitizers ] || { echo "[package] sanitizers is a test build: no package" >&2; exit 2; }
amrsp_run_where_config_belongs scripts/package.sh "$config"
build="$repo/build/$config"
out="$repo/build/packages/$config"
[ -f "$build/CPackConfig.cmake" ] || { echo "[package] no $build/CPackConfig.cmake: run scripts/build.sh $config" >&2; exit 1; }
depends=$(sed -n 's/^AMRSP_DEBIAN_DEPENDS_RESOLVED:INTERNAL=//p' "$build/CMakeCache.txt")
[ -n "$depends" ] || { echo "[package] $config was built against a ParaView/VTK that dpkg does not know: no exact Depends (see $build.configure.log)" >&2; exit 1; }
rm -rf "$out"
mkdir -p "$out"
echo "[package] $config: cpack (Depends: $depends)"
(cd "$build" && cpack -G DEB -B "$out" >"$out/cpack.log" 2>&1) \
  || { tail -n 30 "$out/cpack.log"; echo "[package] cpack failed (log: $out/cpack.log)" >&2; exit 1; }
rm -rf "$out/_CPack_Packages"
debs=("$out"/*.deb)
[ "${#debs[@]}" = 1 ] && [ -f "${debs[0]}" ] || { echo "[package] expected one .deb in $out, found: ${debs[*]}" >&2; exit 1; }
echo "[package] ${debs[0]#"$repo/"}: $(dpkg-deb -f "${debs[0]}" Package Version Depends | paste -sd' ' -), $(dpkg-deb -c "${debs[0]}" | grep -vc '/$') files"
