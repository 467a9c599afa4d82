#!/usr/bin/env bash
# README command 1: renders an AMR dataset to a PNG with the project's renderer.
#   scripts/render.sh [DATASET] [amrsp render options]    (default: a built-in synthetic dataset)
# Installs what is missing, builds the ParaView configuration of this system if needed (Debian 12:
# paraview, 13: trixie-paraview, testing: forky-paraview), then runs `amrsp render`. ParaView builds
# on VTK < 9.4 render through GLX, so an X server is started for them (scripts/start-xvfb.sh); on
# Debian testing (VTK 9.6) the tool renders through EGL when DISPLAY is unset.
set -Eeuo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
. "$repo/scripts/configs.sh"
read -r config _ <<<"$(amrsp_default_configs)" || { echo "[render] $(amrsp_unsupported)" >&2; exit 1; }
"$repo/scripts/install-deps.sh" >/tmp/amrsp-install-deps.log 2>&1 \
  || { tail -n 30 /tmp/amrsp-install-deps.log; echo "[render] installing dependencies failed" >&2; exit 1; }
case "$(amrsp_config_backends "$config")" in
  glx*) . "$repo/scripts/start-xvfb.sh" >/dev/null ;;
esac
"$repo/scripts/build.sh" "$config" >/tmp/amrsp-build.log 2>&1 \
  || { tail -n 40 /tmp/amrsp-build.log; echo "[render] build failed (log: /tmp/amrsp-build.log)" >&2; exit 1; }
args=("$@")
have_output=0
for a in "$@"; do case "$a" in -o|--output|--output=*) have_output=1 ;; esac; done
[ "$have_output" = 1 ] || args+=(-o "$repo/amrsp-render.png")
exec "$repo/build/$config/Tools/amrsp/amrsp" render "${args[@]}"
