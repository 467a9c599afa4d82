#!/usr/bin/env bash
# README command 1: renders an AMR dataset to a PNG with the project's renderer.
#   scripts/render.sh [DATASET] [amrsp render options]    (default: a built-in synthetic dataset)
# Installs what is missing, builds the ParaView configuration if needed, then runs `amrsp render`.
set -Eeuo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
"$repo/scripts/install-deps.sh" >/tmp/amrsp-install-deps.log 2>&1 \
  || { tail -n 30 /tmp/amrsp-install-deps.log; echo "[render] installing dependencies failed" >&2; exit 1; }
. "$repo/scripts/start-xvfb.sh" >/dev/null
"$repo/scripts/build.sh" paraview >/tmp/amrsp-build.log 2>&1 \
  || { tail -n 40 /tmp/amrsp-build.log; echo "[render] build failed (log: /tmp/amrsp-build.log)" >&2; exit 1; }
args=("$@")
have_output=0
for a in "$@"; do case "$a" in -o|--output|--output=*) have_output=1 ;; esac; done
[ "$have_output" = 1 ] || args+=(-o "$repo/amrsp-render.png")
exec "$repo/build/paraview/Tools/amrsp/amrsp" render "${args[@]}"
