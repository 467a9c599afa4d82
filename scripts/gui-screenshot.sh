#!/usr/bin/env bash
# Makes docs/paraview-gui.png: the ParaView GUI with the plugin's "AMR Single-Pass Volume"
# representation on the Enzo moving7 hierarchy, its colour map and opacity function log-scaled,
# and the Color Map Editor open (a documentation helper, not a test). Runs the GUI smoke test's script in a private
# Xvfb (so no other window is in the picture), waits until the GUI has drawn, grabs the screen and
# ends the GUI and that Xvfb. Needs the ParaView build (scripts/build.sh paraview) and the data.
#   scripts/gui-screenshot.sh [OUT.png]
set -Eeuo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
out=${1:-$repo/docs/paraview-gui.png}
plugin="$repo/build/paraview/lib/paraview-5.11/plugins/SinglePassAMRPlugin/SinglePassAMRPlugin.so"
[ -f "$plugin" ] || { echo "gui-screenshot: build the plugin first (scripts/build.sh paraview)" >&2; exit 1; }
display=${AMRSP_SCREENSHOT_DISPLAY:-:97}
n=${display#:}
[ ! -e "/tmp/.X11-unix/X$n" ] || { echo "gui-screenshot: display $display is in use" >&2; exit 1; }
work=$(mktemp -d)
Xvfb "$display" -screen 0 1280x900x24 -nolisten tcp >"$work/xvfb.log" 2>&1 &
xvfb=$!
gui=
cleanup() {
  [ -z "$gui" ] || kill "$gui" 2>/dev/null || true
  kill "$xvfb" 2>/dev/null || true
  wait 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
for _ in $(seq 50); do [ -e "/tmp/.X11-unix/X$n" ] && break; sleep 0.2; done
DISPLAY=$display AMRSP_PLUGIN="$plugin" AMRSP_DATA_DIR="${AMRSP_DATA_DIR:-$repo/../shared/data}" \
  AMRSP_GUI_OUT="$work" AMRSP_TEST_DIR="$repo/Testing/Python" paraview --dr --script="$repo/Testing/Python/GuiSmokeScript.py" \
  >"$work/paraview.log" 2>&1 &
gui=$!
# the script has run when it wrote its status; then give the GUI time to repaint its panels
for _ in $(seq 300); do [ -f "$work/gui-smoke.json" ] && break; sleep 0.2; done
[ -f "$work/gui-smoke.json" ] || { cat "$work/paraview.log" >&2; echo "gui-screenshot: the GUI script did not run" >&2; exit 1; }
sleep "${AMRSP_SCREENSHOT_WAIT:-5}"
tool() { DISPLAY=$display pvpython "$repo/scripts/x11-tool.py" "$@"; }
# No window manager: fill the screen, then (coordinates of ParaView 5.11's default layout at
# 1280x900) collapse the reader's property section, raise the pipeline browser / properties
# splitter and widen the left docks, so that the representation's group is in the picture, and
# open the Color Map Editor (Coloring's Edit button), which shows the log-scale switches.
tool maximize
sleep 3
tool click 97 536
sleep 1
tool drag 146 398 146 225
sleep 1
tool drag 296 500 420 500
sleep 1
tool click 82 531
sleep 2
mkdir -p "$(dirname "$out")"
tool grab "$out" "${AMRSP_SCREENSHOT_WIDTH:-900}"
ls -l "$out"
