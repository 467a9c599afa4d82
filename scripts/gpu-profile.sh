#!/usr/bin/env bash
# The prepared GPU profile, for a lent machine with an NVIDIA GPU (docs/performance.md, "The GPU
# profile"): unpacks build/amrsp-gpu-bundle.tar.xz (scripts/gpu-bundle.sh) and runs
# gpu-check.sh profile, writing gpu-profile.json to $OUT (the device tool's output folder) or to
# the current folder. Prints the device's driver first.
set -uo pipefail
repo=$(cd "$(dirname "$0")/.." && pwd)
bundle=${AMRSP_GPU_BUNDLE:-$repo/build/amrsp-gpu-bundle.tar.xz}
[ -f "$bundle" ] || { echo "FAIL: no $bundle (scripts/build.sh forky-vtk && scripts/gpu-bundle.sh)"; exit 1; }
dest=$(mktemp -d)
if ! tar -xJf "$bundle" -C "$dest" 2>/dev/null; then
  # a machine without xz: Python's lzma unpacks it
  python3 -c 'import sys, tarfile; tarfile.open(sys.argv[1], "r:xz").extractall(sys.argv[2])' \
    "$bundle" "$dest" || { echo "FAIL: cannot unpack $bundle"; exit 1; }
fi
nvidia-smi --query-gpu=name,driver_version,memory.total --format=csv,noheader 2>/dev/null || true
out=${OUT:-$PWD}
"$dest/amrsp-gpu/gpu-check.sh" profile "$out/gpu-profile.json"
