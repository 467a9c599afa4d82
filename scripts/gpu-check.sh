#!/usr/bin/env bash
# Renders with the bundled amrsp on an NVIDIA GPU through EGL (no X server) and prints what the
# README's GPU figures are made of: every method against the CPU reference on the real datasets,
# the shading features, then the paper's dataset 3 and a billion cells with times and peak memory.
#
#   ./gpu-check.sh [quick]        (in the folder scripts/gpu-bundle.sh made; about 5 min, quick 40 s)
#
# A machine whose driver is not under /usr/local/nvidia: set AMRSP_EGL_VENDOR_JSON to its
# glvnd vendor file (10_nvidia.json).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
nv=/usr/local/nvidia
export __EGL_VENDOR_LIBRARY_FILENAMES=${AMRSP_EGL_VENDOR_JSON:-$nv/share/glvnd/egl_vendor.d/10_nvidia.json}
[ -f "$__EGL_VENDOR_LIBRARY_FILENAMES" ] || { echo "FAIL: no EGL vendor file $__EGL_VENDOR_LIBRARY_FILENAMES"; exit 1; }
unset DISPLAY
amrsp=("$here/lib/ld-linux-x86-64.so.2" --library-path "$here/lib:$nv/lib64:$nv/lib:/usr/lib/x86_64-linux-gnu" "$here/amrsp")
keep='^device\|^storage\|^mapper\|^frames\|^rmse\|error\|warn\|Not a valid'
# peak resident memory of one command (python's getrusage of its child)
peak() {
  python3 -c 'import resource, subprocess, sys, time
t = time.time(); r = subprocess.run(sys.argv[1:])
print("wall %.2f s, peak RSS %.3f GB, exit %d" % (time.time() - t, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1e6, r.returncode))' "$@"
}
enzo=$here/data/enzo_moving7/DD0010/moving7_0010.hierarchy
echo "=== real datasets, 256x256: RMSE (0-255) against the CPU reference and the CPU kD-tree"
for d in "$enzo" "$here/data/amrex_plt1_Y" "$here"/data/vthb_hierarchicalbox/*.vthb synthetic:pulse; do
  for m in packing bindless linear multipass; do
    echo "--- $(basename "$d") $m"
    timeout 120 "${amrsp[@]}" render "$d" --method "$m" --size 256x256 --compare --quiet 2>&1 | grep -i "$keep"
  done
done
echo "=== features (Enzo, bindless)"
for o in "--shade on" "--blend iso --iso 0.3,0.6" "--shadows 0.05" "--interpolation smooth" "--blend maximum" "--centering vertex" "--bindless-access waterfall"; do
  echo "--- $o"
  # shellcheck disable=SC2086
  timeout 120 "${amrsp[@]}" render "$enzo" --method bindless --size 256x256 --compare --quiet $o 2>&1 | grep -i "rmse\|error\|Not a valid"
done
[ "${1:-}" = quick ] && exit 0
echo "=== paper dataset 3, 512x512, 5 frames"
for m in packing bindless linear multipass; do
  echo "--- $m"
  timeout 300 peak "${amrsp[@]}" render synthetic:cosmo:grids=39061,levels=13,cells=140M --method "$m" --size 512x512 --repeat 5 --quiet 2>&1 | grep -i "$keep\|peak"
done
echo "=== a billion cells, 512x512, 3 frames"
for m in packing bindless linear multipass; do
  echo "--- $m"
  timeout 300 peak "${amrsp[@]}" render synthetic:cosmo:grids=280000,levels=13,cells=1000M --method "$m" --size 512x512 --repeat 3 --quiet 2>&1 | grep -i "$keep\|peak"
done
