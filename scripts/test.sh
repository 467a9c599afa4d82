#!/usr/bin/env bash
# README command 2: installs what is missing, starts Xvfb if needed, configures and builds both
# configurations (ParaView 5.11 and plain VTK 9.1) and runs every test of both.
set -Eeuo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
echo "[test] installing dependencies (log: /tmp/amrsp-install-deps.log)"
"$repo/scripts/install-deps.sh" >/tmp/amrsp-install-deps.log 2>&1 \
  || { tail -n 40 /tmp/amrsp-install-deps.log; echo "[test] installing dependencies failed" >&2; exit 1; }
. "$repo/scripts/start-xvfb.sh"
status=0
for config in paraview vtk; do
  "$repo/scripts/build.sh" "$config"
  echo "[test] ctest: $config configuration"
  if ! (cd "$repo/build/$config" && ctest --output-on-failure -j "${AMRSP_JOBS:-$(nproc)}"); then
    status=1
  fi
done
if [ "$status" = 0 ]; then echo "[test] all tests of both configurations passed"; else echo "[test] FAILED" >&2; fi
exit $status
