#!/usr/bin/env bash
# Packs the forky-vtk build's `amrsp` (VTK 9.6, EGL: no X server needed) with every library it
# loads, the root's glibc loader and the small real datasets into one .tar.xz, for a machine with
# an NVIDIA GPU and its driver but none of Debian's packages (about 30 MB compressed).
#
#   scripts/gpu-bundle.sh [OUT.tar.xz]        (default build/amrsp-gpu-bundle.tar.xz)
#
# Needs `scripts/build.sh forky-vtk` first. Unpack it there and run scripts/gpu-check.sh from the
# unpacked folder: the bundle's loader runs amrsp against the bundle's libraries, and libglvnd
# finds the GPU's EGL driver through __EGL_VENDOR_LIBRARY_FILENAMES.
set -euo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
. "$repo/scripts/configs.sh"
out=${1:-$repo/build/amrsp-gpu-bundle.tar.xz}
root=$("$repo/scripts/debian-root.sh" forky path)
build=$repo/build/forky-vtk
[ -x "$build/Tools/amrsp/amrsp" ] || { echo "no $build/Tools/amrsp/amrsp: run scripts/build.sh forky-vtk"; exit 1; }
stage=$(mktemp -d)
trap 'rm -rf "$stage"' EXIT
dir=$stage/amrsp-gpu
mkdir -p "$dir/lib" "$dir/data"
cp "$build/Tools/amrsp/amrsp" "$dir/"
cp -L "$build/lib/libvtkSinglePassAMR.so.1" "$dir/lib/"
cp "$repo/scripts/gpu-check.sh" "$dir/"
# the commit the bundle measures (its profile JSON names it)
{ git -C "$repo" rev-parse HEAD 2>/dev/null || echo unknown; } | tr -d '\n' >"$dir/VERSION"
[ -z "$(git -C "$repo" status --porcelain --untracked-files=no 2>/dev/null)" ] || echo " (modified)" >>"$dir/VERSION"
# every library the tool and the module load, as the root's loader resolves them
cp "$dir/amrsp" "$dir/lib/libvtkSinglePassAMR.so.1" "$root/tmp/"
libs=$(chroot "$root" env LD_LIBRARY_PATH=/tmp ldd /tmp/amrsp /tmp/libvtkSinglePassAMR.so.1 |
  awk '$3 ~ /^\// { print $3 }' | sort -u)
rm -f "$root/tmp/amrsp" "$root/tmp/libvtkSinglePassAMR.so.1"
for lib in $libs; do
  [ -e "$dir/lib/$(basename "$lib")" ] || cp -L "$root$lib" "$dir/lib/"
done
# libglvnd's front ends (VTK loads EGL and OpenGL at run time) and the loader itself
multiarch=$(amrsp_multiarch)
for name in libEGL.so.1 libOpenGL.so.0 libGLdispatch.so.0 libGLX.so.0 libGL.so.1; do
  cp -L "$root/usr/lib/$multiarch/$name" "$dir/lib/"
done
cp -L "$root/lib64/ld-linux-x86-64.so.2" "$dir/lib/"
data=$repo/../shared/data
for d in enzo_moving7 amrex_plt1_Y vthb_hierarchicalbox chombo3d_vtm; do
  [ -d "$data/$d" ] && cp -r "$data/$d" "$dir/data/"
done
mkdir -p "$(dirname "$out")"
tar -C "$stage" -cf - amrsp-gpu | xz -T0 -6 > "$out"
echo "wrote $out ($(du -h "$out" | cut -f1)): $(ls "$dir/lib" | wc -l) libraries"
